// What the BVH traversals (closest.cpp, any_hit.cpp) share about the nodes they push
// on their fixed stacks: the stack's bound, a node's links copied before its box test,
// and the prefetch of a pushed node.
// Header-only: these run in the traversal's inner loops and must inline there.
#pragma once
#include <cstdint>
#include <cstring>

#include "rt/bvh/bvh.h"

namespace rt::traversal {

// kWidth - 1 entries per level at most; the builder bounds the depth to 48 levels of
// SAH splits followed by halvings (bvh_build.cpp, kSahDepthLimit): 81 levels for 2^32
// primitives.
constexpr int kStackSize = (BvhNode::kWidth - 1) * 81;

// Starts loading the node a stack entry names while the traversal goes on: the ray
// reaches it after the nearer subtrees, and the traversal mostly waits for node
// loads. Leaves are not prefetched: that measured slower (docs/performance.md).
inline void prefetch_node(const Bvh& bvh, int32_t child) {
    if (child < 0) return;
    const char* p = reinterpret_cast<const char*>(&bvh.nodes[child]);
    for (int line = 0; line < int(sizeof(BvhNode)); line += 64) __builtin_prefetch(p + line);
}

// A node's child links, copied before its box test: the copy's load is issued with
// the boxes' loads instead of waiting for the test's answer to pick a child.
struct NodeLinks {
    alignas(32) int32_t child[BvhNode::kWidth];
    alignas(16) uint16_t count[BvhNode::kWidth];
    explicit NodeLinks(const BvhNode& n) {
        std::memcpy(child, n.child, sizeof child);
        std::memcpy(count, n.count, sizeof count);
    }
};

}  // namespace rt::traversal
