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

    // Ray through the centre of pixel (i, j); i counts columns from the left,
    // j rows from the top. The direction has unit length.
    Ray primary_ray(int i, int j) const {
        Real s_u = left + (right - left) * (Real(i) + Real(0.5)) / Real(width);
        Real s_v = top - (top - bottom) * (Real(j) + Real(0.5)) / Real(height);
        Vec3 d = u * s_u + v * s_v - w * near_distance;
        return {position, normalize(d)};
    }
};

// The loader has already checked the gaze is non-zero and spans a frame with up.
Camera make_camera(const CameraDesc& desc);

}  // namespace rt
