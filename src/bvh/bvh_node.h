// Writing a node's child slots, for the SAH builder (bvh_build.cpp) and the
// collapse (bvh_collapse.cpp). Inline: both write every node through them.
#pragma once
#include "rt/bvh/bvh.h"

namespace rt::bvh_builder {

inline void set_slot(BvhNode& n, int slot, const Box& b) {
    for (int a = 0; a < 3; ++a) {
        n.lo[a][slot] = b.lo[a];
        n.hi[a][slot] = b.hi[a];
    }
}

// Empty slots: boxes that no ray enters, no children.
inline void clear_node(BvhNode& node) {
    for (int i = 0; i < BvhNode::kWidth; ++i) {
        set_slot(node, i, Box());
        node.child[i] = BvhNode::kEmpty;
        node.count[i] = 0;
    }
    for (uint8_t& p : node.pad) p = 0;
}

}  // namespace rt::bvh_builder
