// The collapse into fuller 8-wide nodes (bvh_collapse.cpp), run by the SAH builder
// (bvh_build.cpp) on each node once its subtrees are built.
#pragma once
#include <cstdint>

#include "rt/bvh/bvh.h"

namespace rt::bvh_builder {

// A node's shape, all its parent's collapse needs to rule both steps out: its
// slots in use, plus kOnlyLeaves when every one is a leaf.
constexpr uint8_t kOnlyLeaves = 0x80;
inline uint8_t shape_of(int slots, bool only_leaves) {
    return static_cast<uint8_t>(slots | (only_leaves ? kOnlyLeaves : 0));
}
uint8_t shape_of(const BvhNode& n);  // of a built node

// Steps 1 and 2 for `node`, whose k slots are in use and whose subtrees are built
// and collapsed (`shapes`: the child nodes' shape_of, 0 for a leaf). Returns the
// node's shape_of.
uint8_t collapse_node(NodeArray& nodes, BvhNode& node, int k, const uint8_t shapes[BvhNode::kWidth]);

// After the build: squeezes out removed nodes (new indices keep the order, and a
// node's children come after it, so a node only moves down and its children,
// further on, move after it) and gives back the freed pages. Returns the depth.
int finish_nodes(NodeArray& nodes);

}  // namespace rt::bvh_builder
