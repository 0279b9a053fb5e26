// The traversal's box test (rt/bvh/box_test.h) as the tests call it: box_padding and
// test_node_boxes, declared in rt/bvh/bvh.h.
#include "rt/bvh/box_test.h"

#include "rt/bvh/bvh.h"
#include "rt/bvh/intersect.h"

namespace rt {

using namespace traversal;

double box_padding(const Bvh& bvh, const Ray& ray) {
#if defined(RT_REAL_FLOAT)
    return box_pad(bvh, ray);
#else
    (void)bvh, (void)ray;
    return 0;
#endif
}

int test_node_boxes(const Bvh& bvh, const BvhNode& node, const Ray& ray, Real tmin, Real tmax, Real t[kWidth],
                    bool scalar) {
    const BoxRay br = box_ray(prepare(ray), bvh, tmin);
    alignas(kBoxesAlign) BoxReal bt[kWidth];
    const int mask = scalar ? test_scalar(node, br, BoxReal(tmin), BoxReal(tmax), bt)
                            : test_boxes(node, br, BoxReal(tmin), BoxReal(tmax), bt);
    for (int i = 0; i < kWidth; ++i) t[i] = Real(bt[i]);
    return mask;
}

}  // namespace rt
