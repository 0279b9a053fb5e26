// allocate_bytes (rt/io/memory.h) and the global operator new that uses it.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "rt/io/memory.h"

namespace {

constexpr size_t kHuge = rt::kHugePageBytes;

uintptr_t address(const void* p) { return reinterpret_cast<uintptr_t>(p); }

TEST(Memory, SmallAllocationsHaveTheirAlignment) {
    for (size_t n : {size_t(0), size_t(1), size_t(100), size_t(1) << 20, kHuge - kHuge / 8 - 1}) {
        for (size_t align : {size_t(8), size_t(16), size_t(64), size_t(4096)}) {
            void* p = rt::allocate_bytes(n, align);
            ASSERT_NE(p, nullptr) << n << " bytes aligned to " << align;
            EXPECT_EQ(address(p) % align, 0u) << n << " bytes aligned to " << align;
            std::memset(p, 0xab, n);
            std::free(p);
        }
    }
}

TEST(Memory, LargeAllocationsStartOnAHugePage) {
    for (size_t n : {kHuge - kHuge / 8, size_t(1921024), kHuge, kHuge + kHuge / 4, 8 * kHuge + 1}) {
        auto* p = static_cast<unsigned char*>(rt::allocate_bytes(n, 64));
        ASSERT_NE(p, nullptr) << n;
        EXPECT_EQ(address(p) % kHuge, 0u) << n;
        std::memset(p, 0x5a, n);
        EXPECT_EQ(p[n - 1], 0x5a);
        std::free(p);
    }
}

TEST(Memory, RoundsUpOnlyWhenThatCostsLittle) {
    // An 800x800 RGB image (1.92 MB) fills one huge page: 80 KiB more is under an eighth.
    void* image = rt::allocate_bytes(1921024);
    ASSERT_NE(image, nullptr);
    EXPECT_GE(malloc_usable_size(image), kHuge);
    std::free(image);
    // 2.5 MiB is not rounded to 4 MiB: its last half page stays in small pages.
    void* odd = rt::allocate_bytes(kHuge + kHuge / 4);
    ASSERT_NE(odd, nullptr);
    EXPECT_LT(malloc_usable_size(odd), 2 * kHuge);
    std::free(odd);
}

TEST(Memory, OperatorNewTakesLargeBlocksFromIt) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer keeps its own operator new (src/io/memory.cpp)";
#endif
    // glibc alone returns large blocks 16 bytes into a page (mmap) or anywhere on its heap,
    // on a 2 MiB boundary by a 1 in 2^17 chance: these hold with the replaced operator new.
    std::vector<char> v(3 * kHuge);
    EXPECT_EQ(address(v.data()) % kHuge, 0u);
    std::string s(kHuge, 'x');
    EXPECT_EQ(address(s.data()) % kHuge, 0u);
    auto* a = new double[kHuge / sizeof(double)];
    EXPECT_EQ(address(a) % kHuge, 0u);
    delete[] a;
    std::vector<int> small(10);
    EXPECT_EQ(address(small.data()) % alignof(int), 0u);
}

}  // namespace
