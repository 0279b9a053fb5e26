// Pinhole cameras (spec section 3, "Camera"): w = -gaze, v = up made orthogonal
// to gaze, u = v x w; pixel (i, j) is sampled at its centre.
#pragma once
#include <string>

#include "rt/core/math.h"
#include "rt/loader/scene_desc.h"

namespace rt {

struct Camera {
    Vec3 position, u, v, w;
    Real left = -1, right = 1, bottom = -1, top = 1, near_distance = 1;
    int width = 0, height = 0;
    std::string image_name;

    // Ray through the centre of pixel (i, j); i counts columns from the left,
    // j rows from the top. The direction has unit length.
    Ray primary_ray(int i, int j) const {
        Real s_u = left + (right - left) * (Real(i) + Real(0.5)) / Real(width);
        Real s_v = top - (top - bottom) * (Real(j) + Real(0.5)) / Real(height);
        Vec3 d = u * s_u + v * s_v - w * near_distance;
        return {position, normalize(d)};
    }
};

// The two camera types of the scene file (spec 3) as a CameraDesc: the loader reads and
// checks the values, these set the gaze and the near plane's extents from them.
//
// "lookAt": the gaze runs from Position to `gaze_point`; FovY (degrees) spans a near
// plane symmetric about it vertically, the aspect ratio comes from the resolution.
// Needs d.position, d.near_distance, d.width and d.height set; gaze_point != position
// and 0 < fovy_degrees < 180.
void set_look_at(CameraDesc& d, const Vec3& gaze_point, Real fovy_degrees);
// "simple" (no _type): the gaze and the NearPlane extents as written.
void set_near_plane(CameraDesc& d, const Vec3& gaze, Real left, Real right, Real bottom, Real top);

// Whether `gaze` and `up` (both non-zero) make a camera frame: make_camera's
// u = up x w must not vanish, so up must not be parallel to the gaze.
bool spans_camera_frame(const Vec3& gaze, const Vec3& up);

// The loader has already checked the gaze is non-zero and spans a frame with up.
Camera make_camera(const CameraDesc& desc);

}  // namespace rt
