// Binned SAH build (Wald 2007): at each node, primitive centroids are binned
// along all three axes at once into kBins bins and the plane with the lowest
// surface-area cost is taken; nodes that would cost more split than as a leaf
// become leaves. The build works on float boxes rounded outwards from the
// primitives' Real bounds, so node boxes always contain their primitives.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "rt/bvh.h"

namespace rt {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeaf = 8;    // a leaf never holds more, whatever SAH says
constexpr float kTraversalCost = 1;  // relative to one primitive test
constexpr int kSahDepthLimit = 48;  // beyond it, object-median splits bound the depth

float round_down(Real x) {
    float f = static_cast<float>(x);
    return static_cast<Real>(f) > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float round_up(Real x) {
    float f = static_cast<float>(x);
    return static_cast<Real>(f) < x ? std::nextafter(f, HUGE_VALF) : f;
}

struct FBox {
    float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF};
    float hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
    void extend(const FBox& b) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], b.lo[a]);
            hi[a] = std::max(hi[a], b.hi[a]);
        }
    }
    void extend(const float p[3]) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
    }
    float area() const {
        const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
        return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
    }
};

struct Builder {
    std::vector<FBox> boxes;
    std::vector<float> centres;  // 3 per primitive
    Bvh& bvh;

    void make_leaf(BvhNode& n, uint32_t begin, uint32_t end) {
        n.first = begin;
        n.count = static_cast<uint16_t>(end - begin);
        n.axis = 0;
    }

    void build(uint32_t node_index, uint32_t begin, uint32_t end, int depth) {
        bvh.depth = std::max(bvh.depth, depth + 1);
        FBox box, cbox;
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t p = bvh.prims[i];
            box.extend(boxes[p]);
            cbox.extend(&centres[3 * p]);
        }
        {
            BvhNode& n = bvh.nodes[node_index];
            for (int a = 0; a < 3; ++a) {
                n.lo[a] = box.lo[a];
                n.hi[a] = box.hi[a];
            }
        }
        const uint32_t count = end - begin;
        if (count == 1) return make_leaf(bvh.nodes[node_index], begin, end);

        float extent[3], scale[3];
        for (int a = 0; a < 3; ++a) {
            extent[a] = cbox.hi[a] - cbox.lo[a];
            scale[a] = extent[a] > 0 ? float(kBins) / extent[a] : 0;
        }
        auto bin_of = [&](uint32_t p, int axis) {
            const int b = static_cast<int>((centres[3 * p + axis] - cbox.lo[axis]) * scale[axis]);
            return std::min(std::max(b, 0), kBins - 1);
        };

        // Best SAH split over all axes, binned in one pass.
        int best_axis = -1, best_bin = 0;
        float best_cost = HUGE_VALF;
        if (depth < kSahDepthLimit) {
            FBox bin_box[3][kBins];
            uint32_t bin_count[3][kBins] = {};
            for (uint32_t i = begin; i < end; ++i) {
                const uint32_t p = bvh.prims[i];
                for (int axis = 0; axis < 3; ++axis) {
                    const int b = bin_of(p, axis);
                    ++bin_count[axis][b];
                    bin_box[axis][b].extend(boxes[p]);
                }
            }
            for (int axis = 0; axis < 3; ++axis) {
                if (!(extent[axis] > 0)) continue;
                float right_area[kBins];
                uint32_t right_count[kBins];
                FBox acc;
                uint32_t n = 0;
                for (int b = kBins - 1; b > 0; --b) {
                    acc.extend(bin_box[axis][b]);
                    n += bin_count[axis][b];
                    right_area[b] = acc.area();
                    right_count[b] = n;
                }
                acc = FBox();
                n = 0;
                for (int b = 0; b < kBins - 1; ++b) {
                    acc.extend(bin_box[axis][b]);
                    n += bin_count[axis][b];
                    if (n == 0 || right_count[b + 1] == 0) continue;
                    const float cost = acc.area() * float(n) + right_area[b + 1] * float(right_count[b + 1]);
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
            const float parent_area = box.area();
            const float split_cost = parent_area > 0 ? kTraversalCost + best_cost / parent_area : HUGE_VALF;
            if (split_cost >= float(count) && count <= kMaxLeaf)
                return make_leaf(bvh.nodes[node_index], begin, end);
            auto it = std::partition(bvh.prims.begin() + begin, bvh.prims.begin() + end,
                                     [&](uint32_t p) { return bin_of(p, best_axis) <= best_bin; });
            mid = static_cast<uint32_t>(it - bvh.prims.begin());
        } else {
            // All centroids coincide, or the depth limit was reached: split at the
            // object median of the widest axis, which always makes progress.
            if (count <= kMaxLeaf && depth < kSahDepthLimit) return make_leaf(bvh.nodes[node_index], begin, end);
            const int axis = extent[0] >= extent[1] ? (extent[0] >= extent[2] ? 0 : 2) : (extent[1] >= extent[2] ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(bvh.prims.begin() + begin, bvh.prims.begin() + mid, bvh.prims.begin() + end,
                             [&](uint32_t a, uint32_t b) { return centres[3 * a + axis] < centres[3 * b + axis]; });
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
    Builder b{{}, {}, *this};
    b.boxes.resize(bounds.size());
    b.centres.resize(3 * bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            b.boxes[i].lo[a] = round_down(bounds[i].lo[a]);
            b.boxes[i].hi[a] = round_up(bounds[i].hi[a]);
            b.centres[3 * i + a] = 0.5f * b.boxes[i].lo[a] + 0.5f * b.boxes[i].hi[a];
        }
    }
    nodes.reserve(2 * bounds.size());
    nodes.emplace_back();
    b.build(0, 0, static_cast<uint32_t>(bounds.size()), 0);
    nodes.shrink_to_fit();
}

}  // namespace rt
