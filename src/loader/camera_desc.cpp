#include "rt/loader/camera_desc.h"

#include <cmath>

namespace rt {

void set_look_at(CameraDesc& d, const Vec3& gaze_point, Real fovy_degrees) {
    const Real pi = kPi;
    d.gaze = gaze_point - d.position;
    d.top = d.near_distance * std::tan(fovy_degrees * pi / 360);
    d.bottom = -d.top;
    d.right = d.top * Real(d.width) / Real(d.height);
    d.left = -d.right;
}

void set_near_plane(CameraDesc& d, const Vec3& gaze, Real left, Real right, Real bottom, Real top) {
    d.gaze = gaze;
    d.left = left;
    d.right = right;
    d.bottom = bottom;
    d.top = top;
}

bool spans_camera_frame(const Vec3& gaze, const Vec3& up) {
    return length(cross(normalize(up), normalize(gaze))) > Real(1e-9);
}

}  // namespace rt
