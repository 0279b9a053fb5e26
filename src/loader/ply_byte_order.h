// Loads of the binary PLY body's scalars (ply_binary.cpp): any alignment, byte-swapped
// when the file's byte order differs from the host's. Inline templates: they are the
// inner loops' loads.
#pragma once
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "ply_format.h"

namespace rt::ply_reader {

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
constexpr bool kHostLittleEndian = false;
#else
constexpr bool kHostLittleEndian = true;
#endif

// Loads a T stored at p (any alignment), byte-swapping when Swap.
template <typename T, bool Swap>
inline T load(const unsigned char* p) {
    T v;
    if constexpr (!Swap || sizeof(T) == 1) {
        std::memcpy(&v, p, sizeof v);
    } else if constexpr (sizeof(T) == 2) {
        uint16_t u;
        std::memcpy(&u, p, 2);
        u = __builtin_bswap16(u);
        std::memcpy(&v, &u, 2);
    } else if constexpr (sizeof(T) == 4) {
        uint32_t u;
        std::memcpy(&u, p, 4);
        u = __builtin_bswap32(u);
        std::memcpy(&v, &u, 4);
    } else {
        static_assert(sizeof(T) == 8, "unsupported size");
        uint64_t u;
        std::memcpy(&u, p, 8);
        u = __builtin_bswap64(u);
        std::memcpy(&v, &u, 8);
    }
    return v;
}

// The value of type t at p as R: double for coordinates (any type), int64_t for list
// counts and indices (integer types only, checked when the header is read).
template <class R, bool Swap>
inline R load_as(const unsigned char* p, Type t) {
    switch (t) {
        case Type::I8:
            return load<int8_t, Swap>(p);
        case Type::U8:
            return load<uint8_t, Swap>(p);
        case Type::I16:
            return load<int16_t, Swap>(p);
        case Type::U16:
            return load<uint16_t, Swap>(p);
        case Type::I32:
            return load<int32_t, Swap>(p);
        case Type::U32:
            return load<uint32_t, Swap>(p);
        case Type::F32:
            if constexpr (std::is_floating_point_v<R>) return load<float, Swap>(p);
            break;
        case Type::F64:
            if constexpr (std::is_floating_point_v<R>) return load<double, Swap>(p);
            break;
    }
    return R(0);
}

template <bool Swap>
inline double load_real(const unsigned char* p, Type t) {
    return load_as<double, Swap>(p, t);
}

template <bool Swap>
inline int64_t load_int(const unsigned char* p, Type t) {
    return load_as<int64_t, Swap>(p, t);
}

}  // namespace rt::ply_reader
