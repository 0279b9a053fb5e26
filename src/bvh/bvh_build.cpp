// Binned SAH build (Wald 2007): at each node, primitive centroids are binned
// along each axis into kBins bins and the plane with the lowest surface-area
// cost is taken; nodes that would cost more split than as a leaf become leaves.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "rt/bvh.h"

namespace rt {
namespace {

constexpr int kBins = 32;
constexpr uint32_t kMaxLeaf = 8;      // a leaf never holds more, whatever SAH says
constexpr Real kTraversalCost = 1;    // relative to one primitive test
constexpr int kSahDepthLimit = 48;    // beyond it, object-median splits bound the depth

float round_down(Real x) {
    float f = static_cast<float>(x);
    return static_cast<Real>(f) > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float round_up(Real x) {
    float f = static_cast<float>(x);
    return static_cast<Real>(f) < x ? std::nextafter(f, HUGE_VALF) : f;
}

struct Builder {
    const std::vector<Aabb>& bounds;
    std::vector<Vec3> centres;
    Bvh& bvh;

    void set_bounds(BvhNode& node, const Aabb& b) {
        for (int a = 0; a < 3; ++a) {
            node.lo[a] = round_down(b.lo[a]);
            node.hi[a] = round_up(b.hi[a]);
        }
    }

    void make_leaf(uint32_t node_index, uint32_t begin, uint32_t end) {
        BvhNode& n = bvh.nodes[node_index];
        n.first = begin;
        n.count = static_cast<uint16_t>(end - begin);
        n.axis = 0;
    }

    void build(uint32_t node_index, uint32_t begin, uint32_t end, int depth) {
        bvh.depth = std::max(bvh.depth, depth + 1);
        Aabb box, cbox;
        for (uint32_t i = begin; i < end; ++i) {
            box.extend(bounds[bvh.prims[i]]);
            cbox.extend(centres[bvh.prims[i]]);
        }
        set_bounds(bvh.nodes[node_index], box);
        const uint32_t count = end - begin;
        if (count == 1) return make_leaf(node_index, begin, end);

        // Best SAH split over all axes.
        int best_axis = -1, best_bin = 0;
        Real best_cost = HUGE_VAL;
        const Vec3 extent = cbox.hi - cbox.lo;
        if (depth < kSahDepthLimit) {
            for (int axis = 0; axis < 3; ++axis) {
                if (!(extent[axis] > 0)) continue;
                Aabb bin_box[kBins];
                uint32_t bin_count[kBins] = {};
                const Real scale = Real(kBins) / extent[axis];
                for (uint32_t i = begin; i < end; ++i) {
                    const uint32_t p = bvh.prims[i];
                    int b = static_cast<int>((centres[p][axis] - cbox.lo[axis]) * scale);
                    b = std::min(std::max(b, 0), kBins - 1);
                    ++bin_count[b];
                    bin_box[b].extend(bounds[p]);
                }
                // Sweep from the right, then from the left.
                Real right_area[kBins];
                uint32_t right_count[kBins];
                Aabb acc;
                uint32_t n = 0;
                for (int b = kBins - 1; b > 0; --b) {
                    acc.extend(bin_box[b]);
                    n += bin_count[b];
                    right_area[b] = acc.area();
                    right_count[b] = n;
                }
                acc = Aabb();
                n = 0;
                for (int b = 0; b < kBins - 1; ++b) {
                    acc.extend(bin_box[b]);
                    n += bin_count[b];
                    if (n == 0 || right_count[b + 1] == 0) continue;
                    const Real cost = acc.area() * n + right_area[b + 1] * right_count[b + 1];
                    if (cost < best_cost) {
                        best_cost = cost;
                        best_axis = axis;
                        best_bin = b;
                    }
                }
            }
        }

        uint32_t mid;
        if (best_axis >= 0) {
            const Real parent_area = box.area();
            const Real split_cost =
                parent_area > 0 ? kTraversalCost + best_cost / parent_area : HUGE_VAL;
            if (split_cost >= Real(count) && count <= kMaxLeaf) return make_leaf(node_index, begin, end);
            const Real scale = Real(kBins) / extent[best_axis];
            const Real lo = cbox.lo[best_axis];
            auto it = std::partition(bvh.prims.begin() + begin, bvh.prims.begin() + end, [&](uint32_t p) {
                int b = static_cast<int>((centres[p][best_axis] - lo) * scale);
                return std::min(std::max(b, 0), kBins - 1) <= best_bin;
            });
            mid = static_cast<uint32_t>(it - bvh.prims.begin());
        } else {
            // All centroids coincide, or the depth limit was reached: split at the
            // object median of the widest axis, which always makes progress.
            if (count <= kMaxLeaf && depth < kSahDepthLimit) return make_leaf(node_index, begin, end);
            int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(bvh.prims.begin() + begin, bvh.prims.begin() + mid, bvh.prims.begin() + end,
                             [&](uint32_t a, uint32_t b) { return centres[a][axis] < centres[b][axis]; });
            best_axis = axis;
        }
        if (mid == begin || mid == end) mid = begin + count / 2;

        const uint32_t left = static_cast<uint32_t>(bvh.nodes.size());
        bvh.nodes.emplace_back();
        bvh.nodes.emplace_back();
        BvhNode& n = bvh.nodes[node_index];
        n.first = left;
        n.count = 0;
        n.axis = static_cast<uint16_t>(best_axis);
        build(left, begin, mid, depth + 1);
        build(left + 1, mid, end, depth + 1);
    }
};

}  // namespace

void Bvh::build(const std::vector<Aabb>& bounds) {
    nodes.clear();
    prims.resize(bounds.size());
    std::iota(prims.begin(), prims.end(), 0u);
    depth = 0;
    if (bounds.empty()) return;
    Builder b{bounds, {}, *this};
    b.centres.resize(bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i) b.centres[i] = bounds[i].centre();
    nodes.reserve(2 * bounds.size());
    nodes.emplace_back();
    b.build(0, 0, static_cast<uint32_t>(bounds.size()), 0);
    nodes.shrink_to_fit();
}

}  // namespace rt
