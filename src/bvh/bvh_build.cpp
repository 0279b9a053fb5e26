// BVH construction: a binary tree by binned SAH (Wald 2007), collapsed to a
// 4-wide tree. At each node, centroids are binned along all three axes in one
// pass into kBins bins and the plane with the lowest surface-area cost is
// taken; a node that would cost more split than as a leaf becomes a leaf.
// Primitive boxes are partitioned in place (streaming, no gathers), and large
// subtrees are built on their own threads.
#include <algorithm>
#include <cmath>
#include <thread>

#include "rt/bvh.h"

namespace rt {

float round_down_to_float(Real x) {
    const float f = static_cast<float>(x);
    return static_cast<Real>(f) > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float round_up_to_float(Real x) {
    const float f = static_cast<float>(x);
    return static_cast<Real>(f) < x ? std::nextafter(f, HUGE_VALF) : f;
}

namespace {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeaf = 8;     // a leaf never holds more, whatever SAH says
constexpr float kTraversalCost = 1;  // relative to one primitive test
constexpr int kSahDepthLimit = 48;   // beyond it, object-median splits bound the depth
constexpr uint32_t kParallelMin = 1u << 14;  // smallest subtree worth a thread

struct FBox {
    float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF};
    float hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
    void extend(const float l[3], const float h[3]) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], l[a]);
            hi[a] = std::max(hi[a], h[a]);
        }
    }
    void extend(const FBox& b) { extend(b.lo, b.hi); }
    float area() const {
        const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
        return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
    }
};

// Binary node of the intermediate tree.
struct BNode {
    FBox box;
    uint32_t left = 0, right = 0;  // inner: child indices (same vector)
    uint32_t first = 0, count = 0;  // leaf: range of refs (count > 0)
};

// Centroid doubled (lo + hi): binning only needs a consistent measure.
inline float centre2(const BuildBox& b, int axis) { return b.lo[axis] + b.hi[axis]; }

struct Builder {
    BuildBox* refs;
    unsigned threads_left;  // extra threads this subtree may still start
    int max_depth = 0;

    // Builds refs[begin, end) into `out`; returns the index of its root in `out`.
    uint32_t build(std::vector<BNode>& out, uint32_t begin, uint32_t end, int depth) {
        max_depth = std::max(max_depth, depth + 1);
        FBox box, cbox;
        for (uint32_t i = begin; i < end; ++i) {
            box.extend(refs[i].lo, refs[i].hi);
            const float c[3] = {centre2(refs[i], 0), centre2(refs[i], 1), centre2(refs[i], 2)};
            cbox.extend(c, c);
        }
        const uint32_t index = static_cast<uint32_t>(out.size());
        out.emplace_back();
        out[index].box = box;
        const uint32_t count = end - begin;
        auto leaf = [&]() {
            out[index].first = begin;
            out[index].count = count;
            return index;
        };
        if (count == 1) return leaf();

        float extent[3], scale[3];
        for (int a = 0; a < 3; ++a) {
            extent[a] = cbox.hi[a] - cbox.lo[a];
            scale[a] = extent[a] > 0 ? float(kBins) / extent[a] : 0;
        }
        auto bin_of = [&](const BuildBox& r, int axis) {
            const int b = static_cast<int>((centre2(r, axis) - cbox.lo[axis]) * scale[axis]);
            return std::min(std::max(b, 0), kBins - 1);
        };

        int best_axis = -1, best_bin = 0;
        float best_cost = HUGE_VALF;
        if (depth < kSahDepthLimit) {
            FBox bin_box[3][kBins];
            uint32_t bin_count[3][kBins] = {};
            for (uint32_t i = begin; i < end; ++i) {
                for (int axis = 0; axis < 3; ++axis) {
                    const int b = bin_of(refs[i], axis);
                    ++bin_count[axis][b];
                    bin_box[axis][b].extend(refs[i].lo, refs[i].hi);
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
            if (split_cost >= float(count) && count <= kMaxLeaf) return leaf();
            BuildBox* it = std::partition(refs + begin, refs + end,
                                          [&](const BuildBox& r) { return bin_of(r, best_axis) <= best_bin; });
            mid = static_cast<uint32_t>(it - refs);
        } else {
            // All centroids coincide, or the depth limit was reached: split at the
            // object median of the widest axis, which always makes progress.
            if (count <= kMaxLeaf && depth < kSahDepthLimit) return leaf();
            const int axis =
                extent[0] >= extent[1] ? (extent[0] >= extent[2] ? 0 : 2) : (extent[1] >= extent[2] ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(refs + begin, refs + mid, refs + end, [&](const BuildBox& a, const BuildBox& b) {
                return centre2(a, axis) < centre2(b, axis) || (centre2(a, axis) == centre2(b, axis) && a.id < b.id);
            });
        }
        if (mid == begin || mid == end) mid = begin + count / 2;

        uint32_t left, right;
        if (threads_left > 0 && mid - begin >= kParallelMin && end - mid >= kParallelMin) {
            // Left subtree on a new thread into its own vector, appended afterwards.
            Builder other{refs, (threads_left - 1) / 2};
            threads_left -= 1 + other.threads_left;
            std::vector<BNode> sub;
            uint32_t sub_root = 0;
            std::thread t([&] { sub_root = other.build(sub, begin, mid, depth + 1); });
            right = build(out, mid, end, depth + 1);
            t.join();
            max_depth = std::max(max_depth, other.max_depth);
            const uint32_t offset = static_cast<uint32_t>(out.size());
            for (BNode& n : sub) {
                if (n.count == 0) {
                    n.left += offset;
                    n.right += offset;
                }
                out.push_back(n);
            }
            left = sub_root + offset;
        } else {
            left = build(out, begin, mid, depth + 1);
            right = build(out, mid, end, depth + 1);
        }
        out[index].left = left;
        out[index].right = right;
        return index;
    }
};

// Collapses the binary tree into 4-wide nodes: each 4-wide node takes a binary
// node's children and keeps opening the largest inner one until it has four.
void set_slot(Bvh4Node& n, int slot, const FBox& b) {
    for (int a = 0; a < 3; ++a) {
        n.lo[a][slot] = b.lo[a];
        n.hi[a][slot] = b.hi[a];
    }
}

// A node with four empty slots.
Bvh4Node empty_node() {
    Bvh4Node n{};
    for (int i = 0; i < 4; ++i) {
        set_slot(n, i, FBox());
        n.child[i] = Bvh4Node::kEmpty;
    }
    return n;
}

struct Collapser {
    const std::vector<BNode>& bin;
    std::vector<Bvh4Node>& nodes;
    int depth = 0;

    uint32_t collapse(uint32_t b, int level) {
        depth = std::max(depth, level);
        uint32_t kids[4] = {bin[b].left, bin[b].right, 0, 0};
        int n = 2;
        while (n < 4) {
            int best = -1;
            float best_area = -1;
            for (int i = 0; i < n; ++i) {
                const BNode& k = bin[kids[i]];
                if (k.count == 0 && k.box.area() > best_area) {
                    best_area = k.box.area();
                    best = i;
                }
            }
            if (best < 0) break;
            const uint32_t opened = kids[best];
            kids[best] = bin[opened].left;
            kids[n++] = bin[opened].right;
        }
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        nodes.push_back(empty_node());
        for (int i = 0; i < n; ++i) {
            const BNode& k = bin[kids[i]];
            int32_t child;
            if (k.count > 0) {
                child = ~static_cast<int32_t>(k.first);
            } else {
                child = static_cast<int32_t>(collapse(kids[i], level + 1));
            }
            Bvh4Node& node = nodes[index];  // collapse() may have reallocated
            set_slot(node, i, k.box);
            node.child[i] = child;
            node.count[i] = static_cast<uint16_t>(k.count);
        }
        return index;
    }
};

}  // namespace

void Bvh::build(std::vector<BuildBox>&& boxes) {
    nodes.clear();
    prims.clear();
    depth = 0;
    if (boxes.empty()) return;
    for (size_t i = 0; i < boxes.size(); ++i) boxes[i].id = static_cast<uint32_t>(i);

    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    Builder b{boxes.data(), hw - 1};
    std::vector<BNode> bin;
    bin.reserve(boxes.size() / 2 + 16);
    const uint32_t root = b.build(bin, 0, static_cast<uint32_t>(boxes.size()), 0);

    prims.resize(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) prims[i] = boxes[i].id;
    std::vector<BuildBox>().swap(boxes);

    const FBox& rb = bin[root].box;
    for (int a = 0; a < 3; ++a) {
        root_box.lo[a] = rb.lo[a];
        root_box.hi[a] = rb.hi[a];
    }
    if (bin[root].count > 0) {
        // A single leaf: one 4-wide node with one slot.
        nodes.push_back(empty_node());
        Bvh4Node& node = nodes[0];
        set_slot(node, 0, rb);
        node.child[0] = ~static_cast<int32_t>(bin[root].first);
        node.count[0] = static_cast<uint16_t>(bin[root].count);
        depth = 1;
        return;
    }
    nodes.reserve(bin.size() / 3 + 1);
    Collapser c{bin, nodes};
    c.collapse(root, 1);
    depth = c.depth;
    nodes.shrink_to_fit();
}

}  // namespace rt
