// "Did you mean ...?" for misspelt keys and names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pt {

// Optimal-string-alignment distance (Levenshtein plus adjacent transpositions),
// so "raduis" is one edit from "radius".
int edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word` if it is close enough to be a likely typo
// (case differences are free), else an empty string. A word of fewer than 6
// characters must keep its first letter ("uv0" is not a typo of "v0").
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

// "; did you mean 'x'?" when `word` looks like a typo of a candidate x
// (closest_match), else `otherwise` (e.g. "; expected 'a' or 'b'"), for the
// tail of an "unknown ..." message.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates,
                         std::string otherwise = "");

// "'word'"
std::string quoted(std::string_view word);

// "'a', 'b' or 'c'" (sorted, each once; `conjunction` replaces "or").
std::string quoted_list(std::vector<std::string> items, std::string_view conjunction = "or");

}  // namespace pt
