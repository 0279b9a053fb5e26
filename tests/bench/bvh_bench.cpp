// BVH build benchmark: loads a scene once, then builds its BVH several times and
// prints the median wall time, the median process CPU time (less sensitive to a
// busy machine than wall time) and the tree's SAH cost, the quality measure the
// builder optimises (traversal steps cost 1, primitive tests 1, relative to the
// root box's area), so a faster build can be checked not to have bought its
// speed with a worse tree.
//   build/bench/bvh_bench [--runs N] [--bins N] [--leaf N] [--no-collapse] scene.json
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/scene_build/build_scene.h"

namespace {

double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double area(const rt::BvhNode& n, int i) {
    const double x = double(n.hi[0][i]) - n.lo[0][i], y = double(n.hi[1][i]) - n.lo[1][i],
                 z = double(n.hi[2][i]) - n.lo[2][i];
    return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
}

// Sum over child slots of area * (1 for an inner node, count for a leaf), over the
// root's own area: the expected cost of a random ray that hits the root box.
double sah_cost(const rt::Bvh& bvh) {
    if (bvh.nodes.empty()) return 0;
    double root = 0, sum = 0;
    const rt::BvhNode& r = bvh.nodes[0];
    {
        float lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = HUGE_VALF;
            hi[a] = -HUGE_VALF;
            for (int i = 0; i < rt::BvhNode::kWidth; ++i)
                if (r.child[i] != rt::BvhNode::kEmpty) {
                    lo[a] = std::min(lo[a], r.lo[a][i]);
                    hi[a] = std::max(hi[a], r.hi[a][i]);
                }
        }
        const double x = double(hi[0]) - lo[0], y = double(hi[1]) - lo[1], z = double(hi[2]) - lo[2];
        root = 2 * (x * y + y * z + z * x);
    }
    for (const rt::BvhNode& n : bvh.nodes)
        for (int i = 0; i < rt::BvhNode::kWidth; ++i) {
            if (n.child[i] == rt::BvhNode::kEmpty) continue;
            sum += area(n, i) * (n.is_leaf(i) ? double(n.leaf_size(i)) : 1.0);
        }
    return root > 0 ? 1 + sum / root : 0;
}

// Child slots: inner, leaf, empty; and primitives in leaves.
struct Fill {
    size_t inner = 0, leaves = 0, empty = 0, prims = 0;
};
Fill fill_of(const rt::Bvh& bvh) {
    Fill f;
    for (const rt::BvhNode& n : bvh.nodes)
        for (int i = 0; i < rt::BvhNode::kWidth; ++i) {
            if (n.child[i] == rt::BvhNode::kEmpty)
                ++f.empty;
            else if (n.is_leaf(i))
                ++f.leaves, f.prims += n.leaf_size(i);
            else
                ++f.inner;
        }
    return f;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    rt::BvhBuildOptions opt;
    std::string path;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--bins" && i + 1 < argc)
            opt.bins = std::atoi(argv[++i]);
        else if (a == "--leaf" && i + 1 < argc)
            opt.max_leaf = uint32_t(std::atoi(argv[++i]));
        else if (a == "--no-collapse")
            opt.collapse = false;
        else
            path = a;
    }
    if (path.empty()) {
        std::fprintf(stderr, "usage: bvh_bench [--runs N] [--bins N] [--leaf N] [--no-collapse] scene.json\n");
        return 2;
    }
    try {
        rt::Scene s = rt::build_scene(rt::load_scene(path), opt);
        std::vector<double> wall, cpu;
        double cost = 0;
        size_t nodes = 0;
        Fill fill;
        std::vector<double> box_wall;
        for (int r = 0; r < runs; ++r) {
            const auto b0 = std::chrono::steady_clock::now();
            rt::UninitVector<rt::BuildBox> boxes = rt::primitive_boxes(s.geometry);
            box_wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count());
            rt::Bvh bvh;
            const double c0 = cpu_seconds();
            const auto t0 = std::chrono::steady_clock::now();
            bvh.build(boxes, opt);
            wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            cpu.push_back(cpu_seconds() - c0);
            cost = sah_cost(bvh);
            nodes = bvh.nodes.size();
            fill = fill_of(bvh);
        }
        std::printf(
            "%s: %zu primitives, medians of %d: boxes %.3f s, build %.3f s wall, %.3f s cpu (first %.3f s); "
            "%zu nodes, SAH cost %.4f; fastest %.3f s wall, %.3f s cpu\n",
            path.c_str(), size_t(s.geometry.bounded_count()), runs, median(box_wall), median(wall), median(cpu),
            wall[0], nodes, cost, *std::min_element(wall.begin(), wall.end()),
            *std::min_element(cpu.begin(), cpu.end()));
        const size_t slots = nodes * rt::BvhNode::kWidth;
        std::printf("child slots: %zu inner, %zu leaves (%.2f primitives each), %zu empty (%.1f%%)\n", fill.inner,
                    fill.leaves, fill.leaves ? double(fill.prims) / double(fill.leaves) : 0.0, fill.empty,
                    slots ? 100.0 * double(fill.empty) / double(slots) : 0.0);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
