// A camera as the scene file gives it (spec 3, "Camera"), and the reading of its two
// types into one form; the renderer's camera is made from it (rt/camera/camera.h).
#pragma once
#include <string>

#include "rt/core/math.h"

namespace rt {

// NumSamples' and --samples' bound.
constexpr int kMaxSamples = 1 << 20;

struct CameraDesc {
    Vec3 position, gaze, up;                          // gaze is a direction (lookAt cameras: GazePoint - Position)
    Real left = -1, right = 1, bottom = -1, top = 1;  // near plane extents
    Real near_distance = 1;
    int width = 0, height = 0;
    std::string image_name;
    // Distribution ray tracing (docs/conventions.md, "Assignment 3"). num_samples 0: the
    // camera has no NumSamples and takes one ray through each pixel's centre; otherwise
    // that many random samples per pixel, averaged. aperture_size 0: a pinhole; otherwise
    // a thin lens, a square of that side about Position, focused at focus_distance.
    int num_samples = 0;
    Real aperture_size = 0, focus_distance = 0;
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

}  // namespace rt
