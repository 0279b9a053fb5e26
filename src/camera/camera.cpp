#include "rt/camera/camera.h"

namespace rt {

// spec section 3: w = -gaze/|gaze|, u = v' x w, v = w x u (Up re-orthogonalised).
Camera make_camera(const CameraDesc& d) {
    Camera c;
    c.position = d.position;
    c.w = -normalize(d.gaze);
    c.u = normalize(cross(normalize(d.up), c.w));
    c.v = cross(c.w, c.u);
    c.left = d.left;
    c.right = d.right;
    c.bottom = d.bottom;
    c.top = d.top;
    c.near_distance = d.near_distance;
    c.width = d.width;
    c.height = d.height;
    c.image_name = d.image_name;
    c.samples = d.num_samples;
    c.aperture = d.aperture_size;
    c.focus_distance = d.focus_distance;
    return c;
}

}  // namespace rt
