// The candidate closest in spelling to an unknown name, for "did you mean"
// in error messages (configuration keys, environment parameters).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bsg {

// The candidate at the smallest Levenshtein distance from `unknown` if that is
// a likely typo (at most 2 edits, or a third of the word), else "".
std::string closest_name(std::string_view unknown, const std::vector<std::string_view>& candidates);

}  // namespace bsg
