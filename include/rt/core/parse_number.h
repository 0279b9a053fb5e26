// std::from_chars for numbers in text (scene values, ASCII PLY bodies). Floating-point
// values come from std::from_chars where the C++ library has it, and from fast_float
// (Debian's libfast-float-dev, the same correctly rounded parse) where it does not:
// Emscripten's libc++ (the browser build, docs/web.md). Both give the same double for the
// same text; a literal beyond the type's range is result_out_of_range in both.
#pragma once
#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>
#include <type_traits>

#if defined(__EMSCRIPTEN__)
#include <fast_float/fast_float.h>
#endif

namespace rt {

template <class T>
std::from_chars_result parse_number(const char* first, const char* last, T& value) {
#if defined(__EMSCRIPTEN__)
    if constexpr (std::is_floating_point_v<T>) {
        const auto r = fast_float::from_chars(first, last, value);
        std::from_chars_result out{r.ptr, r.ec};
        if (out.ec != std::errc()) return out;
        // fast_float rounds an out-of-range literal to infinity or zero without saying so.
        const char* p = first;
        if (p < r.ptr && (*p == '-' || *p == '+')) ++p;
        const bool spelled_inf = p < r.ptr && (*p == 'i' || *p == 'I');
        bool nonzero_digit = false;
        for (const char* q = p; q < r.ptr && *q != 'e' && *q != 'E'; ++q) nonzero_digit |= *q >= '1' && *q <= '9';
        if ((std::isinf(value) && !spelled_inf) || (value == 0 && nonzero_digit))
            out.ec = std::errc::result_out_of_range;
        return out;
    } else {
        return std::from_chars(first, last, value);
    }
#else
    return std::from_chars(first, last, value);
#endif
}

}  // namespace rt
