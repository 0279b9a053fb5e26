// BVH tests on the course's official meshes (bunny, ton_Roosendaal, cornellbox), when the
// shared folder is present (shared_dir(): $RT_SHARED_DIR or ../shared): the tree is well
// formed, and closest_hit, any_hit and their packet forms agree with brute force on camera
// rays, rays through vertices and edges, and shadow rays towards the scene's lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bvh_test_support.h"
#include "rt/geometry/traverse.h"
#include "rt/loader/load_scene.h"
#include "rt/scene_build/build_scene.h"
#include "test_support.h"

namespace {

using namespace bvh_test;

// --- official meshes -------------------------------------------------------------------

void check_official(const std::string& rel, int rays, size_t min_triangles) {
    SKIP_UNLESS_SHARED(rel);
    const std::string path = shared_dir() + "/scenes/hw1/" + rel;
    ASSERT_TRUE(file_exists(path)) << path << " is missing from the course's shared folder";
    const rt::Scene s = rt::build_scene(rt::load_scene(path));
    ASSERT_GE(s.geometry.triangles.size(), min_triangles) << path;
    check_structure(s);

    Rng rng(99);
    Checker ck{s};
    // Scene bounds, from the mesh vertices.
    const Real inf = std::numeric_limits<Real>::infinity();
    Vec3 lo{inf, inf, inf}, hi = -lo;
    for (const Vec3& p : s.geometry.positions) {
        lo = rt::vmin(lo, p);
        hi = rt::vmax(hi, p);
    }
    const Vec3 size = hi - lo;
    for (int k = 0; k < rays; ++k) {
        rt::Ray r;
        if (k % 3 == 0) {
            // Camera rays through random pixels.
            const rt::Camera& cam = s.setup.cameras[pick(rng, s.setup.cameras.size())];
            r = cam.primary_ray(static_cast<int>(pick(rng, size_t(cam.width))),
                                static_cast<int>(pick(rng, size_t(cam.height))));
        } else {
            const Vec3 org{lo.x + size.x * uniform(rng, -0.5, 1.5), lo.y + size.y * uniform(rng, -0.5, 1.5),
                           lo.z + size.z * uniform(rng, -0.5, 1.5)};
            Vec3 target;
            if (k % 3 == 1) {
                target = s.geometry.positions[pick(rng, s.geometry.positions.size())];  // through a vertex
            } else {
                const rt::Triangle& tri = s.geometry.triangles[pick(rng, s.geometry.triangles.size())];
                const Vec3 a = s.geometry.positions[tri.v[0]], b = s.geometry.positions[tri.v[1]];
                target = a + (b - a) * uniform(rng, 0, 1);  // through an edge
            }
            const Vec3 d = target - org;
            if (!(rt::length(d) > 0)) continue;
            r = {org, rt::normalize(d)};
        }
        ck.closest(r, 0, HUGE_VAL);
        ck.collect(r);
        if (k % 3 == 0) {
            // The camera rays of the pixel and the next ones in its row (up to kPacket): a
            // coherent packet; and the 4 x 4 pixels from it, the renderer's packet (render.cpp).
            const rt::Camera& cam = s.setup.cameras[0];
            const int x = static_cast<int>(pick(rng, size_t(cam.width))),
                      y = static_cast<int>(pick(rng, size_t(cam.height)));
            rt::Ray row[rt::kPacket];
            int n = 0;
            for (; n < rt::kPacket && x + n < cam.width; ++n) row[n] = cam.primary_ray(x + n, y);
            ck.packet(row, n, 0, HUGE_VAL);
            n = 0;
            for (int py = y; py < std::min(y + 4, cam.height); ++py)
                for (int px = x; px < std::min(x + 4, cam.width); ++px) row[n++] = cam.primary_ray(px, py);
            ck.packet(row, n, 0, HUGE_VAL);
            const std::vector<Vec3> points = ck.hit_points(row, n);
            for (const rt::Light& light : s.setup.lights) ck.shadow_packet(points, light.position, rng);
        }
        ck.any(r, 0, HUGE_VAL);
        const Real span = rt::length(size);
        const Real tmin = uniform(rng, 0, span), tmax = tmin + uniform(rng, 0, span);
        ck.any(r, tmin, tmax);
    }
    ck.finish();
    EXPECT_EQ(ck.mismatches, 0) << "of " << ck.queries << " queries on " << path;
    EXPECT_GT(ck.hits, ck.closest_queries / 20) << path;
}

TEST(BvhOfficial, Bunny) { check_official("bunny.json", 300, 4000); }

TEST(BvhOfficial, TonRoosendaal) { check_official("akif_uslu/ton_Roosendaal_smooth.json", 60, 10000); }

// Axis-aligned walls (flat boxes) and spheres.
TEST(BvhOfficial, CornellBox) { check_official("cornellbox.json", 600, 10); }

}  // namespace
