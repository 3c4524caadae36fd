// The `learner:` preset (docs/algorithms.md#quirk-switches): `learner: corrected`
// turns on every switch that corrects one of the original's quirks (Q1, Q4,
// Q5, Q10, Q19, Q20) in one word, so that a run file or a sweep can ask for the
// corrected learner without listing them. `learner: faithful` (the default)
// changes nothing.
//
// Precedence: the preset overrides the algorithm and environment files; a
// switch named in the run file or with --set (a grid's fixed keys and axes
// are --set arguments) keeps its own value, so that e.g. `learner: corrected`
// with `rescale_value_output: false` is the corrected learner without Q19.
#pragma once

#include <string_view>
#include <utility>
#include <vector>

namespace bsg {

// (key, value as YAML text) of every switch `learner: corrected` sets, in
// quirk order; keys that do not apply to an algorithm are skipped for it.
const std::vector<std::pair<std::string_view, std::string_view>>& corrected_learner_settings();

}  // namespace bsg
