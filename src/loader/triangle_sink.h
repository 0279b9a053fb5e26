// The PLY reader's triangle output (ply_binary.cpp and ply_ascii.cpp write to it).
// The index vector is sized up front for the expected triangles (resize, not
// reserve, so the hot loops store through a plain pointer); polygons that need
// more room grow it; finish() trims it to what was written. Everything here is
// inline: the body decoders' inner loops call it per triangle.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__GNUC__)
#define RT_PLY_COLD __attribute__((cold, noinline))
#else
#define RT_PLY_COLD
#endif

namespace rt::ply_reader {

class TriangleSink {
public:
    TriangleSink(std::vector<uint32_t>& v, size_t expected_indices) : v_(v) {
        v_.resize(expected_indices);
        cur_ = v_.data();
        end_ = cur_ + v_.size();
    }
    uint32_t* cursor() const { return cur_; }
    uint32_t* limit() const { return end_; }
    void set_cursor(uint32_t* c) { cur_ = c; }

    void put(uint32_t a, uint32_t b, uint32_t c) {
        if (end_ - cur_ < 3) grow();
        cur_[0] = a;
        cur_[1] = b;
        cur_[2] = c;
        cur_ += 3;
    }
    void finish() { v_.resize(static_cast<size_t>(cur_ - v_.data())); }

private:
    RT_PLY_COLD void grow() {
        const size_t used = static_cast<size_t>(cur_ - v_.data());
        v_.resize(v_.size() + v_.size() / 2 + 3);
        cur_ = v_.data() + used;
        end_ = v_.data() + v_.size();
    }

    std::vector<uint32_t>& v_;
    uint32_t* cur_;
    uint32_t* end_;
};

// Fan-splits one polygon as its vertex indices arrive: vertex k >= 2 makes the
// triangle (first, previous, k).
struct Fan {
    uint32_t first = 0, prev = 0;
    void add(int64_t k, uint32_t u, TriangleSink& tris) {
        if (k == 0) {
            first = u;
        } else if (k >= 2) {
            tris.put(first, prev, u);
        }
        prev = u;
    }
};

}  // namespace rt::ply_reader
