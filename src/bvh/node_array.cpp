// NodeArray (rt/bvh/bvh.h): the builder's node memory.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <new>

#include "rt/bvh/bvh.h"
#include "rt/io/memory.h"

namespace rt {

// The node array of a large scene spans hundreds of megabytes that rays visit
// at random: with 4 KiB pages nearly every node load below the top levels is
// also a TLB miss. 2 MiB pages (transparent huge pages, where the kernel grants
// them on request) cover it with few TLB entries, which makes large scenes render
// faster at no cost to the build (docs/performance.md). The triangles, boxes and
// primitive order are not asked the same: it made loading slower, and rays no
// faster.
void NodeArray::allocate(size_t capacity) {
    data_.reset();
    size_ = 0;
    const size_t bytes = capacity * sizeof(BvhNode);
    void* p = allocate_bytes(bytes, alignof(BvhNode));
    if (!p) throw std::bad_alloc();
    data_.reset(static_cast<BvhNode*>(p));
    bytes_ = bytes;
}

void NodeArray::release_unused() {
    const uintptr_t page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
    const uintptr_t start = reinterpret_cast<uintptr_t>(data_.get());
    // Only pages wholly inside the allocation: a partial page may hold the allocator's data.
    const uintptr_t from = (start + size_ * sizeof(BvhNode) + page - 1) / page * page;
    const uintptr_t to = (start + bytes_) / page * page;
    if (to > from) madvise(reinterpret_cast<void*>(from), to - from, MADV_DONTNEED);
}

void NodeArray::Free::operator()(BvhNode* p) const { std::free(p); }

}  // namespace rt
