// Near misses: which of a few valid words a misspelt one was probably meant to be, for
// "unknown key ignored (did you mean DiffuseReflectance?)" and "required key is missing".
#pragma once
#include <string>
#include <vector>

namespace rt {

// Edit distance between `a` and `b` ignoring letter case: insertions, deletions,
// substitutions and swaps of two neighbouring characters cost 1 each (optimal string
// alignment), so "DiffuseReflectence", "Raduis" and "radius" are each 1 or 0 from the key.
size_t edit_distance_nocase(const std::string& a, const std::string& b);

// The word of `valid` that `word` most likely misspells, or "" when none is close: a
// case-only difference, or an edit distance of at most 1 for words of up to 4 characters
// and at most 2 for longer ones. Ties go to the first in `valid`. `word` itself (exact
// match) is never suggested.
std::string near_miss(const std::string& word, const std::vector<std::string>& valid);

}  // namespace rt
