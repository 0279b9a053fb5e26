// BVH construction by binned SAH (Wald 2007), building the tree of
// BvhNode::kWidth-wide nodes directly: a node starts as one range of primitives and
// keeps splitting its largest splittable child until it has kWidth. A split bins the
// centroids along all three axes in one pass (SIMD), takes the plane of lowest
// surface-area cost, and partitions the range in place, accumulating both sides'
// bounds as it goes, so each split reads the primitives twice. A child that would
// cost more split than as a leaf becomes a leaf (a leaf's cost counted as its leaf
// test goes: triangles in blocks of BvhBuildOptions::block, other shapes one by
// one). Large subtrees are built on their own threads; nodes come from one array
// through an atomic counter.
//
// This file is the SAH builder and Bvh::build. Beside it: box8.h, the box that
// binning and partitioning keep in a register; bvh_node.h, writing a node's slots;
// bvh_collapse.cpp, the collapse of each built node into fuller nodes;
// node_array.cpp, the node memory.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "box8.h"
#include "bvh_collapse.h"
#include "bvh_node.h"
#include "rt/bvh/bvh.h"
#include "rt/core/threads.h"

namespace rt {
namespace bvh_builder {
namespace {

// Most bins per axis (BvhBuildOptions::bins, 16 by default, for large ranges).
constexpr int kBins = 16;

// Bins for a range of `count` primitives: the per-split constant cost (clearing,
// sweeping) dominates small ranges, where few bins already find the best plane.
// The leaf size limit and the traversal cost are BvhBuildOptions (8 and 1).
inline int bins_for(uint32_t count, int max_bins) {
    return std::min(max_bins, count >= 32 ? kBins : std::max(4, static_cast<int>(count / 2)));
}
constexpr int kSahDepthLimit = 48;             // beyond it, object-median splits bound the depth
constexpr uint32_t kParallelMin = 1u << 15;    // smallest subtree worth a thread
constexpr uint32_t kParallelSplit = 1u << 20;  // smallest range whose split is shared by two threads

// Centroid doubled (lo + hi): binning only needs a consistent measure.
inline float centre2(const BuildBox& b, int axis) { return b.lo[axis] + b.hi[axis]; }

// A range of primitives with its bounds and the bounds of its centroids.
struct Range {
    uint32_t begin = 0, end = 0;
    Box box, cbox;
    bool leaf = false;   // decided: stays a leaf
    uint32_t alone = 0;  // how many of its primitives are BuildBox::alone
    uint32_t count() const { return end - begin; }
};

struct Builder {
    BuildBox* refs;
    uint32_t* prims;  // Bvh::prims: each leaf writes its primitives' ids when it is made
    NodeArray& nodes;
    std::atomic<uint32_t>& next_node;
    std::atomic<int>& spare_threads;
    BvhBuildOptions opt;

    // SAH: r stays a leaf when its best split, of cost `best` (the sum of each
    // side's area times its leaf cost), costs no less than testing its
    // primitives, and a leaf may hold them.
    bool stays_leaf(const Range& r, float best) const {
        const float parent_area = r.box.area();
        const float split_cost = parent_area > 0 ? opt.traversal_cost + best / parent_area : HUGE_VALF;
        return split_cost >= leaf_cost(r.count(), r.alone) && r.count() <= opt.max_leaf;
    }

    // The cost of testing n primitives of which `alone` are BuildBox::alone in one
    // leaf: the others in blocks of `block`, as the leaf test takes them.
    float leaf_cost(uint32_t n, uint32_t alone) const { return float((n - alone + opt.block - 1) / opt.block + alone); }

    // Bins r's centroids along all axes; returns false when r should stay a leaf,
    // otherwise the best axis and bin.
    bool best_split(const Range& r, int level, int& axis_out, int& bin_out, float scale[3], int nb) const {
        const uint32_t count = r.count();
        float extent[3];
        for (int a = 0; a < 3; ++a) {
            extent[a] = r.cbox.hi[a] - r.cbox.lo[a];
            scale[a] = extent[a] > 0 ? float(nb) / extent[a] : 0;
        }
        if (count <= 1) return false;
        axis_out = -1;
        if (opt.sah && level < kSahDepthLimit) {
            float best_cost = HUGE_VALF;
            int best_axis = -1, best_bin = 0;
            Box8 bins[3][kBins];
            uint32_t counts[3][kBins], alones[3][kBins];
            bin_all(r, scale, nb, bins, counts, alones);
            for (int axis = 0; axis < 3; ++axis) {
                if (!(extent[axis] > 0)) continue;
                float right_area[kBins];
                uint32_t right_count[kBins], right_alone[kBins];
                Box8 acc = empty8();
                uint32_t n = 0, alone = 0;
                for (int b = nb - 1; b > 0; --b) {
                    acc = min8(acc, bins[axis][b]);
                    n += counts[axis][b];
                    alone += alones[axis][b];
                    right_area[b] = area8(acc);
                    right_count[b] = n;
                    right_alone[b] = alone;
                }
                acc = empty8();
                n = 0;
                alone = 0;
                for (int b = 0; b < nb - 1; ++b) {
                    acc = min8(acc, bins[axis][b]);
                    n += counts[axis][b];
                    alone += alones[axis][b];
                    if (n == 0 || right_count[b + 1] == 0) continue;
                    const float cost = area8(acc) * leaf_cost(n, alone) +
                                       right_area[b + 1] * leaf_cost(right_count[b + 1], right_alone[b + 1]);
                    if (cost < best_cost) {
                        best_cost = cost;
                        best_axis = axis;
                        best_bin = b;
                    }
                }
            }
            if (best_axis >= 0) {
                if (stays_leaf(r, best_cost)) return false;
                axis_out = best_axis;
                bin_out = best_bin;
                return true;
            }
        }
        // All centroids coincide, or the depth limit was reached: object median.
        return count > opt.max_leaf || level >= kSahDepthLimit;
    }

    // Bins r's centroids along all three axes: bins[axis][bin] is the box of the
    // primitives whose centroid falls in that bin, counts[axis][bin] their number,
    // alones[axis][bin] how many of them are BuildBox::alone.
    // Every primitive is binned, not a sample of a large range: a sample misses
    // the few large primitives, such as a floor under a scanned mesh, that
    // dominate the areas, and the tree costs more.
    void bin_all(const Range& r, const float scale[3], int nb, Box8 bins[3][kBins], uint32_t counts[3][kBins],
                 uint32_t alones[3][kBins]) const {
        if (r.count() >= kParallelSplit) {
            // Each half on its own thread, then the bins merged (min and sum do
            // not depend on the order, so neither does the tree).
            const uint32_t half = r.begin + r.count() / 2;
            Box8 other[3][kBins];
            uint32_t other_counts[3][kBins], other_alones[3][kBins];
            in_parallel([&] { bin_range(r, r.begin, half, scale, nb, other, other_counts, other_alones); },
                        [&] { bin_range(r, half, r.end, scale, nb, bins, counts, alones); });
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < nb; ++b) {
                    bins[a][b] = min8(bins[a][b], other[a][b]);
                    counts[a][b] += other_counts[a][b];
                    alones[a][b] += other_alones[a][b];
                }
            return;
        }
        bin_range(r, r.begin, r.end, scale, nb, bins, counts, alones);
    }

    // bin_all over refs[begin, end) of r.
    void bin_range(const Range& r, uint32_t begin, uint32_t end, const float scale[3], int nb, Box8 bins[3][kBins],
                   uint32_t counts[3][kBins], uint32_t alones[3][kBins]) const {
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < nb; ++b) {
                bins[a][b] = empty8();
                counts[a][b] = 0;
                alones[a][b] = 0;
            }
        const bool mixed = r.alone > 0;  // else every alones[][] stays 0
#if defined(__AVX__)
        // bin_of on three axes at once (the same float operations, so the same bins)
        const __m128 cmin = _mm_setr_ps(r.cbox.lo[0], r.cbox.lo[1], r.cbox.lo[2], 0);
        const __m128 sc = _mm_setr_ps(scale[0], scale[1], scale[2], 0);
        const __m128i zero = _mm_setzero_si128(), top = _mm_set1_epi32(nb - 1);
        auto one = [&](uint32_t i) {
            const Box8 v = load8(refs[i]);
            __m128i k = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(centre4(v), cmin), sc));
            k = _mm_min_epi32(_mm_max_epi32(k, zero), top);
            const int b[3] = {_mm_cvtsi128_si32(k), _mm_extract_epi32(k, 1), _mm_extract_epi32(k, 2)};
            for (int a = 0; a < 3; ++a) {
                bins[a][b[a]] = min8(bins[a][b[a]], v);
                ++counts[a][b[a]];
                if (mixed) alones[a][b[a]] += refs[i].alone;
            }
        };
#else
        auto one = [&](uint32_t i) {
            const Box8 v = load8(refs[i]);
            for (int a = 0; a < 3; ++a) {
                const int b = bin_of(refs[i], a, r.cbox.lo[a], scale[a], nb);
                bins[a][b] = min8(bins[a][b], v);
                ++counts[a][b];
                if (mixed) alones[a][b] += refs[i].alone;
            }
        };
#endif
        for (uint32_t i = begin; i < end; ++i) one(i);
    }

    // The bin of b's centroid along `axis`, as the split's partition decides it.
    static int bin_of(const BuildBox& b, int axis, float lo, float scale, int nb) {
        const int k = static_cast<int>((centre2(b, axis) - lo) * scale);
        return std::min(std::max(k, 0), nb - 1);
    }

    // refs[begin, end) partitioned in place: [begin, mid) goes left, with the
    // bounds of both sides' boxes and centroids.
    struct Parted {
        uint32_t mid = 0;
        uint32_t lalone = 0;  // BuildBox::alone primitives that went left
        Box8 lbox = empty8(), lcen = empty8(), rbox = empty8(), rcen = empty8();
    };
    template <class GoesLeft>
    Parted partition(uint32_t begin, uint32_t end, const GoesLeft& goes_left) const {
        // Two-sided: each element's side is final when a pointer passes it, and
        // its bounds go to that side then, so no further pass is needed.
        Parted p;
        auto add_left = [&](const BuildBox& b) {
            const Box8 v = load8(b);
            p.lbox = min8(p.lbox, v);
            p.lcen = min8(p.lcen, centroid8(v));
            p.lalone += b.alone;
        };
        auto add_right = [&](const BuildBox& b) {
            const Box8 v = load8(b);
            p.rbox = min8(p.rbox, v);
            p.rcen = min8(p.rcen, centroid8(v));
        };
        uint32_t i = begin, j = end;
        while (true) {
            while (i < j && goes_left(refs[i])) add_left(refs[i++]);
            while (i < j && !goes_left(refs[j - 1])) add_right(refs[--j]);
            if (i >= j) break;
            std::swap(refs[i], refs[j - 1]);
            add_left(refs[i++]);
            add_right(refs[--j]);
        }
        p.mid = i;
        return p;
    }

    // split() for two or three primitives, where binning's fixed cost buys
    // nothing (and a large share of a mesh's splits are of these): every way to
    // split them is one primitive against the rest, so SAH is evaluated exactly
    // for each.
    bool split_tiny(Range& r, Range& left, Range& right) const {
        const uint32_t n = r.count();
        if (n <= 1) {
            r.leaf = true;
            return false;
        }
        BuildBox* p = refs + r.begin;
        float best = HUGE_VALF;
        uint32_t alone = 0;
        for (uint32_t k = 0; k < (n == 2 ? 1u : n); ++k) {
            Box one, rest;
            for (uint32_t i = 0; i < n; ++i) (i == k ? one : rest).extend(p[i].lo, p[i].hi);
            const float cost = one.area() + rest.area() * leaf_cost(n - 1, r.alone - p[k].alone);
            if (cost < best) {
                best = cost;
                alone = k;
            }
        }
        if (stays_leaf(r, best)) {
            r.leaf = true;
            return false;
        }
        std::swap(p[0], p[alone]);
        left = Range{r.begin, r.begin + 1, {}, {}, false};
        right = Range{r.begin + 1, r.end, {}, {}, false};
        bounds(left);
        bounds(right);
        return true;
    }

    // Splits r into two ranges (with their bounds); r is marked a leaf instead
    // when SAH prefers that.
    bool split(Range& r, int level, Range& left, Range& right) const {
        if (r.count() <= 3 && opt.sah && level < kSahDepthLimit) return split_tiny(r, left, right);
        int axis = -1, bin = 0;
        float scale[3];
        const int nb = bins_for(r.count(), opt.bins);
        if (!best_split(r, level, axis, bin, scale, nb)) {
            r.leaf = true;
            return false;
        }
        uint32_t mid;
        if (axis >= 0) {
            // In-place two-sided partition: bin <= best goes left.
            const float lo = r.cbox.lo[axis], sc = scale[axis];
            auto goes_left = [&](const BuildBox& b) { return bin_of(b, axis, lo, sc, nb) <= bin; };
            Parted p;
            if (r.count() >= kParallelSplit) {
                // Each half partitioned on its own thread; then the right part of
                // the first half and the left part of the second trade places
                // (the shorter block is swapped with the far end of the longer).
                const uint32_t half = r.begin + r.count() / 2;
                Parted q;
                in_parallel([&] { q = partition(r.begin, half, goes_left); },
                            [&] { p = partition(half, r.end, goes_left); });
                const uint32_t a_right = half - q.mid, b_left = p.mid - half;
                if (a_right <= b_left)
                    std::swap_ranges(refs + q.mid, refs + half, refs + p.mid - a_right);
                else
                    std::swap_ranges(refs + q.mid, refs + q.mid + b_left, refs + half);
                p.mid = q.mid + b_left;
                p.lalone += q.lalone;
                p.lbox = min8(p.lbox, q.lbox);
                p.lcen = min8(p.lcen, q.lcen);
                p.rbox = min8(p.rbox, q.rbox);
                p.rcen = min8(p.rcen, q.rcen);
            } else {
                p = partition(r.begin, r.end, goes_left);
            }
            left = Range{};
            right = Range{};
            left.box = to_box(p.lbox);
            left.cbox = to_box(p.lcen);
            right.box = to_box(p.rbox);
            right.cbox = to_box(p.rcen);
            left.alone = p.lalone;
            right.alone = r.alone - p.lalone;
            mid = p.mid;
            if (mid != r.begin && mid != r.end) {
                left.begin = r.begin;
                left.end = mid;
                right.begin = mid;
                right.end = r.end;
                return true;
            }
        } else {
            const Vec3 e{r.cbox.hi[0] - r.cbox.lo[0], r.cbox.hi[1] - r.cbox.lo[1], r.cbox.hi[2] - r.cbox.lo[2]};
            const int a = e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
            mid = r.begin + r.count() / 2;
            std::nth_element(refs + r.begin, refs + mid, refs + r.end, [&](const BuildBox& x, const BuildBox& y) {
                return centre2(x, a) < centre2(y, a) || (centre2(x, a) == centre2(y, a) && x.id < y.id);
            });
        }
        if (mid == r.begin || mid == r.end) mid = r.begin + r.count() / 2;
        left = Range{r.begin, mid, {}, {}, false};
        right = Range{mid, r.end, {}, {}, false};
        bounds(left);
        bounds(right);
        return true;
    }

    // Slot i of `node` becomes the leaf of r's primitives.
    void make_leaf(BvhNode& node, int i, const Range& r) const {
        node.child[i] = ~static_cast<int32_t>(r.begin);
        node.count[i] = static_cast<uint16_t>(r.count());
        for (uint32_t j = r.begin; j < r.end; ++j) prims[j] = refs[j].id;
    }

    // r's bounds; with `number`, also gives each box its id, its index (the root
    // range, before any sorting: one pass over the boxes instead of two).
    void bounds(Range& r, bool number = false) const {
        Box box, cbox;
        r.alone = 0;
        for (uint32_t i = r.begin; i < r.end; ++i) {
            if (number) refs[i].id = i;
            r.alone += refs[i].alone;
            box.extend(refs[i].lo, refs[i].hi);
            const float c[3] = {centre2(refs[i], 0), centre2(refs[i], 1), centre2(refs[i], 2)};
            cbox.extend(c, c);
        }
        r.box = box;
        r.cbox = cbox;
    }

    // Builds the node at `index` from a range already split into `l` and `rr`;
    // returns its shape_of.
    uint8_t build(uint32_t index, Range l, Range rr, int level) {
        // kids[i] is a leaf, or carries its own split in halves[i].
        constexpr int kWidth = BvhNode::kWidth;
        Range kids[kWidth], halves[kWidth][2];
        bool is_split[kWidth] = {};
        int n = 0;
        kids[n++] = l;
        kids[n++] = rr;
        auto evaluate = [&](int i) {
            if (kids[i].leaf || is_split[i]) return;
            is_split[i] = split(kids[i], level + 1, halves[i][0], halves[i][1]);
        };
        // Open the largest child that splits until there are kWidth.
        while (n < kWidth) {
            int best = -1;
            float best_area = -1;
            for (int i = 0; i < n; ++i) {
                evaluate(i);
                if (is_split[i] && kids[i].box.area() > best_area) {
                    best_area = kids[i].box.area();
                    best = i;
                }
            }
            if (best < 0) break;
            kids[n] = halves[best][1];
            kids[best] = halves[best][0];
            is_split[best] = is_split[n] = false;
            ++n;
        }
        for (int i = 0; i < n; ++i) evaluate(i);

        BvhNode& node = nodes[index];
        clear_node(node);
        // Take every child's node index before building any subtree.
        uint32_t child_index[kWidth] = {};
        for (int i = 0; i < n; ++i) {
            set_slot(node, i, kids[i].box);
            if (!is_split[i]) {
                make_leaf(node, i, kids[i]);
            } else {
                child_index[i] = next_node.fetch_add(1, std::memory_order_relaxed);
                node.child[i] = static_cast<int32_t>(child_index[i]);
            }
        }
        // With a spare thread, split the subtrees between it and this thread:
        // largest first, each to the side holding fewer primitives so far.
        uint64_t total = 0;
        for (int i = 0; i < n; ++i)
            if (is_split[i]) total += kids[i].count();
        bool to_helper[kWidth] = {};
        uint8_t shapes[kWidth] = {};  // of the child nodes
        HelperThread helper;
        if (total >= 2 * uint64_t(kParallelMin) && take_thread()) {
            int order[kWidth], m = 0;
            for (int i = 0; i < n; ++i)
                if (is_split[i]) order[m++] = i;
            for (int a = 1; a < m; ++a)  // largest first (at most kWidth)
                for (int b = a; b > 0 && kids[order[b]].count() > kids[order[b - 1]].count(); --b)
                    std::swap(order[b], order[b - 1]);
            uint64_t mine = 0, theirs = 0;
            for (int k = 0; k < m; ++k) {
                const int i = order[k];
                if (theirs <= mine) {
                    to_helper[i] = true;
                    theirs += kids[i].count();
                } else {
                    mine += kids[i].count();
                }
            }
            helper = HelperThread([&, level] {
                for (int i = 0; i < n; ++i)
                    if (to_helper[i]) shapes[i] = build(child_index[i], halves[i][0], halves[i][1], level + 1);
                spare_threads.fetch_add(1);
            });
        }
        for (int i = 0; i < n; ++i)
            if (is_split[i] && !to_helper[i]) shapes[i] = build(child_index[i], halves[i][0], halves[i][1], level + 1);
        helper.join();
        if (opt.collapse) return collapse_node(nodes, node, n, shapes);
        return shape_of(n, std::none_of(is_split, is_split + n, [](bool b) { return b; }));
    }

    // Runs a on a spare thread, when there is one, beside b on this thread;
    // both are done on return.
    template <class A, class B>
    void in_parallel(const A& a, const B& b) const {
        if (!take_thread()) {
            a();
            b();
            return;
        }
        rt::in_parallel(a, b);
        spare_threads.fetch_add(1);
    }

    bool take_thread() const {
        int s = spare_threads.load();
        while (s > 0)
            if (spare_threads.compare_exchange_weak(s, s - 1)) return true;
        return false;
    }
};

}  // namespace
}  // namespace bvh_builder

void Bvh::build(BuildBox* boxes, size_t count, const BvhBuildOptions& options) {
    using namespace bvh_builder;
    nodes.clear();
    prims.clear();
    depth = 0;
    block = 0;
    extent = 0;
    bounds = Box{};
    if (count == 0) return;
    const uint32_t n = static_cast<uint32_t>(count);

    // Every inner node has >= 2 children and every leaf >= 1 primitive, so a
    // tree over n primitives has fewer than n nodes; pages never written
    // are never touched.
    nodes.allocate(n + 1);
    std::atomic<uint32_t> next{1};
    std::atomic<int> spare{static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) - 1};
    BvhBuildOptions opt = options;
    opt.max_leaf = std::min<uint32_t>(std::max<uint32_t>(opt.max_leaf, 1), 1024);  // BvhNode::count is 16 bits
    opt.bins = std::min(std::max(opt.bins, 2), kBins);
    opt.block = block = opt.block_for(n);
    prims.resize(n);
    Builder b{boxes, prims.data(), nodes, next, spare, opt};
    Range root{0, n, {}, {}, false};
    b.bounds(root, true);
    Range l, r;
    if (b.split(root, 1, l, r)) {
        b.build(0, l, r, 1);
    } else {
        // Few primitives that SAH keeps together: one node with one leaf slot.
        BvhNode& node = nodes[0];
        clear_node(node);
        set_slot(node, 0, root.box);
        b.make_leaf(node, 0, root);
    }
    nodes.set_size(next.load());
    depth = finish_nodes(nodes);
    for (int i = 0; i < BvhNode::kWidth; ++i) {
        if (nodes[0].child[i] == BvhNode::kEmpty) continue;
        for (int a = 0; a < 3; ++a) {
            extent = std::max(extent, std::max(std::fabs(nodes[0].lo[a][i]), std::fabs(nodes[0].hi[a][i])));
            bounds.lo[a] = std::min(bounds.lo[a], nodes[0].lo[a][i]);
            bounds.hi[a] = std::max(bounds.hi[a], nodes[0].hi[a][i]);
        }
    }
}

}  // namespace rt
