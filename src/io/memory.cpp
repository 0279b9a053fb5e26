#include "rt/io/memory.h"

#include <sys/mman.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cstdlib>
#include <new>

namespace rt {
namespace {
#if defined(__EMSCRIPTEN__)
constexpr bool kHugePagesExist = false;  // WebAssembly's linear memory: plain allocations
#else
constexpr bool kHugePagesExist = true;
#endif
}  // namespace

void* allocate_bytes(size_t n, size_t align) noexcept {
    constexpr size_t kHuge = kHugePageBytes;
    if (n < kHuge - kHuge / 8 || !kHugePagesExist) {
        if (align <= alignof(std::max_align_t)) return std::malloc(n ? n : 1);
        void* p = nullptr;
        return posix_memalign(&p, std::max(align, sizeof(void*)), n) == 0 ? p : nullptr;
    }
    const size_t whole = n / kHuge * kHuge;
    const size_t rounded = whole == n ? n : whole + kHuge;
    if (rounded - n <= std::min(n / 8, size_t(256) << 10)) n = rounded;
    void* p = nullptr;
    if (posix_memalign(&p, kHuge, n) != 0) return nullptr;
    // A request: refused on some kernels (or THP turned off), harmless then.
    madvise(p, n / kHuge * kHuge, MADV_HUGEPAGE);
    return p;
}

void release_free_memory() noexcept {
#if defined(__GLIBC__)
    ::malloc_trim(0);
#endif
}

}  // namespace rt

// g++ says AddressSanitizer by __SANITIZE_ADDRESS__, clang (make fuzz) by __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define RT_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RT_UNDER_ASAN 1
#endif
#endif

#if !defined(RT_REAL_FLOAT) && !defined(RT_SECONDARY_COPY) && !defined(RT_UNDER_ASAN) && !defined(__EMSCRIPTEN__)
// The global operator new, replaced (C++17 [new.delete.single]) by one that takes its
// memory from allocate_bytes: every std::vector, string and new-expression of the
// program gets huge pages when it is large. libstdc++'s other forms (new[], nothrow)
// call this one, and its other deletes call the two below; the aligned forms
// (std::align_val_t) stay libstdc++'s own. operator delete is replaced too, although
// libstdc++'s also calls std::free: tools that track the pairing (valgrind) then see
// malloc and free on both sides. Compiled in the primary double copy of the library
// only: the other copies (src/io/memory.cpp again, in namespace rt_float, rt_avx2, ...)
// must not define it a second time. Not under AddressSanitizer (make check-asan), whose own operator
// new and delete must pair with each other to check them, nor in the browser build.
void* operator new(std::size_t n) {
    for (;;) {
        if (void* p = rt::allocate_bytes(n)) return p;
        std::new_handler handler = std::get_new_handler();
        if (!handler) throw std::bad_alloc();
        handler();
    }
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif
