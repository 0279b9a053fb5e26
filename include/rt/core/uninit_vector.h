// Storage that is never zero-filled.
//
// UninitVector: a std::vector whose resize() leaves new elements of trivial types unwritten,
// for the large arrays the loader fills from several threads: a zero-filling
// resize would take every page fault on one thread (16M triangles: 768 MB of
// triangles and boxes, about half a second) before the threads write anyway.
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace rt {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
    using std::allocator<T>::allocator;
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    // resize(n) default-initialises: nothing is written for trivial types.
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

template <class T>
using UninitVector = std::vector<T, DefaultInitAllocator<T>>;

// Raw bytes, allocated once and never zero-filled, that hold one array of a
// trivial type at a time: emplace<T>(n) begins the lifetime of an array of n
// default-initialised T (nothing is written) in place of whatever the bytes held
// before, which is gone from then on. Nothing is ever read through another type
// than the one it was written as; only the bytes (and their touched pages) are
// reused. build_scene holds the BVH build's primitive boxes here, then the
// leaf-order vertices (rt/geometry/leaf_vertices.h).
class ReusableStorage {
public:
    ReusableStorage() = default;
    explicit ReusableStorage(size_t bytes)
        : bytes_(bytes ? static_cast<std::byte*>(::operator new(bytes)) : nullptr), capacity_(bytes) {}

    size_t capacity() const { return capacity_; }

    template <class T>
    T* emplace(size_t n) {
        static_assert(std::is_trivially_default_constructible<T>::value && std::is_trivially_destructible<T>::value,
                      "the storage never runs constructors or destructors");
        static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__, "operator new's alignment must do");
        if (n > capacity_ / sizeof(T)) throw std::length_error("ReusableStorage: array larger than the storage");
        if (n == 0) return nullptr;
        return ::new (static_cast<void*>(bytes_.get())) T[n];
    }

private:
    struct Free {
        void operator()(std::byte* p) const { ::operator delete(p); }
    };
    std::unique_ptr<std::byte, Free> bytes_;
    size_t capacity_ = 0;
};

}  // namespace rt
