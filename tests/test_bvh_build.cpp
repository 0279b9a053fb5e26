// BVH build tests (include/rt/bvh/bvh.h, src/bvh/bvh_build.cpp): the SAH prices a leaf as
// its test goes (triangles in blocks, other shapes one by one), the collapse into wide
// nodes keeps the leaves and fills the nodes, and build_scene drops degenerate triangles,
// counts them and builds a well-formed tree over the rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "bvh_test_support.h"
#include "rt/bvh/bvh.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace bvh_test;

// shapes (BuildBox::alone) one by one. Four unit boxes 10 apart along x, block 4:
// as triangles a leaf of four costs one block test, less than any split (at least
// the traversal cost 1 plus the children's share), so they stay one leaf; as
// spheres it costs 4, and the split 2 | 2 costs 1 + (46 * 2 + 46 * 2) / 126 = 2.46
// (box areas: both halves 2 (11 + 1 + 11) = 46, all four 2 (31 + 1 + 31) = 126).
TEST(BvhBuild, LeavesPriceSpheresOneByOne) {
    for (const bool alone : {false, true}) {
        SCOPED_TRACE(alone ? "spheres" : "triangles");
        std::vector<rt::BuildBox> boxes;
        for (int i = 0; i < 4; ++i) {
            rt::Box b;
            b.lo[0] = float(10 * i), b.lo[1] = 0, b.lo[2] = 0;
            b.hi[0] = float(10 * i + 1), b.hi[1] = 1, b.hi[2] = 1;
            boxes.push_back(rt::BuildBox::of(b, alone));
        }
        rt::BvhBuildOptions options;
        options.block = 4;
        rt::Bvh bvh;
        bvh.build(boxes.data(), boxes.size(), options);
        ASSERT_EQ(bvh.nodes.size(), 1u);
        uint32_t largest = 0;
        int slots = 0;
        for (int k = 0; k < rt::BvhNode::kWidth; ++k)
            if (bvh.nodes[0].child[k] != rt::BvhNode::kEmpty) {
                ++slots;
                ASSERT_TRUE(bvh.nodes[0].is_leaf(k));
                largest = std::max(largest, bvh.nodes[0].leaf_size(k));
            }
        EXPECT_EQ(slots, alone ? 4 : 1);
        EXPECT_EQ(largest, alone ? 1u : 4u);
    }
}

// The collapse (bvh_build.cpp) merges and takes in nodes but never changes a leaf:
// with and without it the same leaves (range, size, box) over the same primitive
// order; fewer nodes; the node visits the SAH counts (inner slots' areas) no
// more; and no node is left with a child node whose slots would fit in its own.
struct TreeSummary {
    std::vector<std::tuple<uint32_t, uint32_t, std::vector<float>>> leaves;
    double inner_area = 0;
};
TreeSummary summarise(const rt::Bvh& bvh) {
    TreeSummary t;
    for (const rt::BvhNode& n : bvh.nodes)
        for (int k = 0; k < rt::BvhNode::kWidth; ++k) {
            if (n.child[k] == rt::BvhNode::kEmpty) continue;
            rt::Box b;
            for (int a = 0; a < 3; ++a) b.lo[a] = n.lo[a][k], b.hi[a] = n.hi[a][k];
            if (n.is_leaf(k))
                t.leaves.emplace_back(~static_cast<uint32_t>(n.child[k]), n.leaf_size(k),
                                      std::vector<float>{b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]});
            else
                t.inner_area += b.area();
        }
    std::sort(t.leaves.begin(), t.leaves.end());
    return t;
}
int used_slots(const rt::BvhNode& n) {
    int k = 0;
    while (k < rt::BvhNode::kWidth && n.child[k] != rt::BvhNode::kEmpty) ++k;
    return k;
}

TEST(BvhBuild, CollapseKeepsTheLeavesAndFillsTheNodes) {
    for (const bool clustered : {false, true})
        for (const int n : {40, 3000, 40000}) {
            SCOPED_TRACE(std::to_string(n) + (clustered ? " clustered boxes" : " boxes"));
            Rng rng(uint64_t(n) * 7 + clustered);
            std::vector<rt::BuildBox> boxes;
            for (int i = 0; i < n; ++i) {
                const Real c = clustered ? Real(pick(rng, 20)) : 0;
                Vec3 lo{uniform(rng, c, c + 10), uniform(rng, c, c + 10), uniform(rng, -10, 10)};
                const Vec3 hi = lo + Vec3{uniform(rng, 0, 0.5), uniform(rng, 0, 0.5), uniform(rng, 0, 0.5)};
                boxes.push_back(rt::BuildBox::of(rt::Box::around(lo, hi), i % 17 == 0));
            }
            rt::Bvh plain, collapsed;
            rt::BvhBuildOptions off, on;
            off.collapse = false;
            std::vector<rt::BuildBox> copy = boxes;
            plain.build(copy.data(), copy.size(), off);
            copy = boxes;
            collapsed.build(copy.data(), copy.size(), on);

            EXPECT_EQ(collapsed.prims, plain.prims);
            const TreeSummary a = summarise(plain), b = summarise(collapsed);
            EXPECT_TRUE(a.leaves == b.leaves) << a.leaves.size() << " leaves without, " << b.leaves.size() << " with";
            EXPECT_LE(b.inner_area, a.inner_area);
            EXPECT_LE(collapsed.depth, plain.depth);
            if (n >= 3000) {
                EXPECT_LT(collapsed.nodes.size(), plain.nodes.size());
            }
            size_t fits = 0;
            for (const rt::BvhNode& nd : collapsed.nodes)
                for (int k = 0; k < rt::BvhNode::kWidth; ++k)
                    if (nd.child[k] >= 0 &&
                        used_slots(nd) - 1 + used_slots(collapsed.nodes[nd.child[k]]) <= rt::BvhNode::kWidth)
                        ++fits;
            EXPECT_EQ(fits, 0u) << "child nodes that fit in their parent";
        }
}

TEST(BvhProperty, DegenerateTrianglesAreDroppedAndCounted) {
    rt::SceneDesc d;
    d.materials.push_back({});
    rt::MeshDesc m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    m.indices = {0, 1, 2,   // fine
                 0, 1, 1,   // two equal vertices
                 0, 1, 3,   // collinear
                 2, 2, 2};  // a point
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    EXPECT_EQ(s.geometry.triangles.size(), 1u);
    EXPECT_EQ(s.report.degenerate_triangles, 3u);
    check_structure(s);
}

}  // namespace
