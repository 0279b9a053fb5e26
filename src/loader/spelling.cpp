// Near-miss suggestions for misspelt keys (rt/loader/spelling.h).
#include "rt/loader/spelling.h"

#include <algorithm>
#include <cctype>

namespace rt {

size_t edit_distance_nocase(const std::string& a, const std::string& b) {
    const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
    const size_t n = a.size(), m = b.size();
    // Three rows of the dynamic-programming table: i-2, i-1, i.
    std::vector<size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
    for (size_t j = 0; j <= m; ++j) prev[j] = j;
    for (size_t i = 1; i <= n; ++i) {
        cur[0] = i;
        for (size_t j = 1; j <= m; ++j) {
            const bool same = lower(a[i - 1]) == lower(b[j - 1]);
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
                cur[j] = std::min(cur[j], prev2[j - 2] + 1);
        }
        std::swap(prev2, prev);
        std::swap(prev, cur);
    }
    return prev[m];
}

std::string near_miss(const std::string& word, const std::vector<std::string>& valid) {
    std::string best;
    size_t best_d = 0;
    for (const std::string& v : valid) {
        if (v == word) return "";
        const size_t limit = std::min(word.size(), v.size()) <= 4 ? 1 : 2;
        const size_t d = edit_distance_nocase(word, v);
        if (d <= limit && (best.empty() || d < best_d)) {
            best = v;
            best_d = d;
        }
    }
    return best;
}

}  // namespace rt
