// The collapse (bvh_collapse.h): fewer, fuller nodes.
#include "bvh_collapse.h"

#include <algorithm>
#include <vector>

#include "bvh_node.h"

namespace rt::bvh_builder {

// Collapsing: fewer, fuller nodes. Splitting top-down leaves most nodes at the
// bottom with a few leaves each (a range just over max_leaf becomes a node of two
// leaves): at 16M triangles nearly half the child slots were empty (docs/performance.md).
// So once a node's subtrees are built, the node
//  1. merges two child nodes that hold only leaves into one when their leaves fit
//     one node and the box around both has less surface area than the two boxes
//     (SAH: fewer expected node visits), the pair with the largest saving first;
//  2. takes in a child node whose slots fit in its free ones (one node visit
//     fewer and no box test more: a node tests all its slots at once), the
//     largest box first.
// Leaves, their boxes and primitives stay as built, and hits do not depend on the
// tree's shape (closest_hit breaks ties by primitive id). Removed nodes are marked
// (first slot empty) and squeezed out at the end (finish_nodes).
uint8_t shape_of(const BvhNode& n) {
    int k = 0;
    bool leaves = true;
    for (; k < BvhNode::kWidth && n.child[k] != BvhNode::kEmpty; ++k) leaves = leaves && n.child[k] < 0;
    return shape_of(k, leaves);
}

namespace {

// A child slot as the collapse handles it.
struct Slot {
    Box box;
    float area = 0;
    int32_t child = BvhNode::kEmpty;
    uint16_t count = 0;
    uint8_t shape = 0;  // a child node's shape_of
    bool only_leaves() const { return child >= 0 && (shape & kOnlyLeaves) != 0; }
    int slots() const { return shape & ~kOnlyLeaves; }
};

// The slots of `n` in use; their child nodes' shapes are `shapes` when given,
// else read from the child nodes.
int load_slots(const NodeArray& nodes, const BvhNode& n, Slot s[BvhNode::kWidth], const uint8_t* shapes) {
    int k = 0;
    for (; k < BvhNode::kWidth && n.child[k] != BvhNode::kEmpty; ++k) {
        for (int a = 0; a < 3; ++a) {
            s[k].box.lo[a] = n.lo[a][k];
            s[k].box.hi[a] = n.hi[a][k];
        }
        s[k].area = s[k].box.area();
        s[k].child = n.child[k];
        s[k].count = n.count[k];
        s[k].shape = n.child[k] < 0 ? 0 : shapes ? shapes[k] : shape_of(nodes[n.child[k]]);
    }
    return k;
}

void store_slots(BvhNode& n, const Slot s[BvhNode::kWidth], int k) {
    clear_node(n);
    for (int i = 0; i < k; ++i) {
        set_slot(n, i, s[i].box);
        n.child[i] = s[i].child;
        n.count[i] = s[i].count;
    }
}

void mark_removed(BvhNode& n) { n.child[0] = BvhNode::kEmpty; }
bool is_removed(const BvhNode& n) { return n.child[0] == BvhNode::kEmpty; }

}  // namespace

uint8_t collapse_node(NodeArray& nodes, BvhNode& node, int k, const uint8_t shapes[BvhNode::kWidth]) {
    constexpr int kWidth = BvhNode::kWidth;
    {  // Most nodes hold only leaves: rule both steps out without reading a node.
        int smallest = kWidth + 1, smallest_leafy = kWidth + 1;
        bool pair = false, leaves = true;
        for (int i = 0; i < k; ++i) {
            if (shapes[i] == 0) continue;  // a leaf
            leaves = false;
            const int slots = shapes[i] & ~kOnlyLeaves;
            smallest = std::min(smallest, slots);
            if (!(shapes[i] & kOnlyLeaves)) continue;
            pair = pair || smallest_leafy + slots <= kWidth;
            smallest_leafy = std::min(smallest_leafy, slots);
        }
        if (!pair && k - 1 + smallest > kWidth) return shape_of(k, leaves);
    }
    Slot s[kWidth];
    load_slots(nodes, node, s, shapes);
    for (;;) {  // 1. merge
        int best_a = -1, best_b = -1;
        float best = 0;
        Box best_box;
        for (int a = 0; a < k; ++a) {
            if (!s[a].only_leaves()) continue;
            for (int b = a + 1; b < k; ++b) {
                if (!s[b].only_leaves() || s[a].slots() + s[b].slots() > kWidth) continue;
                Box both = s[a].box;
                both.extend(s[b].box);
                const float saving = s[a].area + s[b].area - both.area();
                if (saving > best) best = saving, best_a = a, best_b = b, best_box = both;
            }
        }
        if (best_a < 0) break;
        Slot into[kWidth], from[kWidth];
        const int ka = load_slots(nodes, nodes[s[best_a].child], into, nullptr);
        const int kb = load_slots(nodes, nodes[s[best_b].child], from, nullptr);
        std::copy(from, from + kb, into + ka);
        store_slots(nodes[s[best_a].child], into, ka + kb);
        mark_removed(nodes[s[best_b].child]);
        s[best_a].box = best_box;
        s[best_a].area = best_box.area();
        s[best_a].shape = shape_of(ka + kb, true);
        std::copy(s + best_b + 1, s + k, s + best_b);
        --k;
    }
    for (;;) {  // 2. take in
        int best = -1;
        for (int i = 0; i < k; ++i)
            if (s[i].child >= 0 && k - 1 + s[i].slots() <= kWidth && (best < 0 || s[i].area > s[best].area)) best = i;
        if (best < 0) break;
        BvhNode& c = nodes[s[best].child];
        Slot t[kWidth];
        const int kc = load_slots(nodes, c, t, nullptr);
        mark_removed(c);
        s[best] = t[0];
        std::copy(t + 1, t + kc, s + k);
        k += kc - 1;
    }
    store_slots(node, s, k);
    return shape_of(node);
}

// After the build: squeezes out removed nodes (new indices keep the order, and a
// node's children come after it, so a node only moves down and its children,
// further on, move after it) and gives back the freed pages. Returns the depth.
int finish_nodes(NodeArray& nodes) {
    const size_t n = nodes.size();
    std::vector<uint32_t> index(n);
    uint32_t kept = 0;
    for (size_t i = 0; i < n; ++i) index[i] = is_removed(nodes[i]) ? ~0u : kept++;
    std::vector<uint8_t> level(kept, 0);
    level[0] = 1;
    int depth = 1;
    for (size_t i = 0; i < n; ++i) {
        if (index[i] == ~0u) continue;
        BvhNode& node = nodes[i];
        const uint32_t to = index[i];
        depth = std::max(depth, int(level[to]));
        for (int c = 0; c < BvhNode::kWidth; ++c)
            if (node.child[c] >= 0) {
                node.child[c] = static_cast<int32_t>(index[node.child[c]]);
                level[node.child[c]] = static_cast<uint8_t>(level[to] + 1);
            }
        if (to != i) nodes[to] = node;
    }
    nodes.set_size(kept);
    nodes.release_unused();
    return depth;
}

}  // namespace rt::bvh_builder
