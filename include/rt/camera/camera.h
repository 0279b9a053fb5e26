// Pinhole cameras (spec section 3, "Camera"): w = -gaze, v = up made orthogonal
// to gaze, u = v x w; pixel (i, j) is sampled at its centre.
#pragma once
#include <string>

#include "rt/core/math.h"
#include "rt/loader/camera_desc.h"

namespace rt {

struct Camera {
    Vec3 position, u, v, w;
    Real left = -1, right = 1, bottom = -1, top = 1, near_distance = 1;
    int width = 0, height = 0;
    std::string image_name;
    // Distribution ray tracing (CameraDesc): samples per pixel (0: one ray through the
    // centre), the square aperture's side (0: a pinhole) and the focus distance.
    int samples = 0;
    Real aperture = 0, focus_distance = 0;

    // Ray through the centre of pixel (i, j); i counts columns from the left,
    // j rows from the top. The direction has unit length.
    Ray primary_ray(int i, int j) const { return pixel_ray(i, j, Real(0.5), Real(0.5)); }

    // Ray through point (dx, dy) of pixel (i, j), each in [0, 1) from its top-left corner,
    // from point (lx, ly) of the lens (each in [0, 1), its corner at -u -v), at `time`
    // (docs/conventions.md, "Assignment 3"): the pinhole ray's point at FocusDistance
    // along the gaze stays sharp.
    Ray sample_ray(int i, int j, Real dx, Real dy, Real lx, Real ly, Real time) const {
        Ray r = pixel_ray(i, j, dx, dy);
        r.time = time;
        if (aperture > 0) {
            const Vec3 focus = r.org + r.dir * (focus_distance / -dot(r.dir, w));
            r.org = position + (u * (lx - Real(0.5)) + v * (ly - Real(0.5))) * aperture;
            r.dir = normalize(focus - r.org);
        }
        return r;
    }

private:
    Ray pixel_ray(int i, int j, Real dx, Real dy) const {
        Real s_u = left + (right - left) * (Real(i) + dx) / Real(width);
        Real s_v = top - (top - bottom) * (Real(j) + dy) / Real(height);
        Vec3 d = u * s_u + v * s_v - w * near_distance;
        return {position, normalize(d)};
    }
};

// The loader has already checked the gaze is non-zero and spans a frame with up.
Camera make_camera(const CameraDesc& desc);

}  // namespace rt
