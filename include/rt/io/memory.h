// Memory for the large arrays (meshes, boxes, BVH nodes, images, PNG buffers).
//
// A page fault costs microseconds, on virtual machines several: a process that
// touches a gigabyte of new 4 KiB pages spends a large part of its time in them
// (docs/performance.md, "huge pages"). allocate_bytes backs every large allocation with
// 2 MiB transparent huge pages where the kernel grants them (madvise(MADV_HUGEPAGE);
// refused or not configured, the pages stay small and nothing else changes): one
// fault per 2 MiB instead of 512. The global operator new goes through it
// (src/io/memory.cpp), so every std::vector and string does (but under
// AddressSanitizer, which keeps its own).
#pragma once
#include <cstddef>

namespace rt {

inline constexpr size_t kHugePageBytes = size_t(2) << 20;

// n bytes aligned to `align` (a power of two of at most kHugePageBytes), released by
// std::free; nullptr when memory runs out. Allocations of at least 7/8 of a huge page
// start on a huge-page boundary and ask for huge pages for every whole one they span;
// one is rounded up to whole huge pages when that adds at most an eighth of it and at
// most 256 KiB (so an 800x800 image's 1.92 MB takes one 2 MiB page, and a gigabyte
// array adds nothing to the peak memory), and its last partial huge page otherwise
// stays in small pages.
void* allocate_bytes(size_t n, size_t align = alignof(std::max_align_t)) noexcept;

// Hands the free pages of the C heap back to the system (glibc's malloc_trim; nothing
// elsewhere). Called where many small blocks were just freed, a scene file's parse tree
// above all: the allocator keeps them otherwise, and the memory of the large arrays
// allocated next (meshes, BVH) would come on top of them.
void release_free_memory() noexcept;

}  // namespace rt
