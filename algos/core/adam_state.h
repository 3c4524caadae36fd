// One codec for an Adam optimiser's state (common/adam.h: first moment m, second moment v, step
// count t) in the checkpoints. Two encodings exist on disk and both are kept byte for byte:
//   binary   m, v (vectors of the optimiser's size), t (i64): the value nets (actor_critic.h) and
//            every network of the off-policy learners, inside a BinaryWriter payload;
//   entries  named scalars of an algorithm's state() (algorithm.h), in one of two layouts:
//            AdamEntryLayout::moments_then_step   "<prefix>m", "<prefix>v", "<prefix>t" of a
//                                                  one-parameter Adam (a Lagrange multiplier's);
//            AdamEntryLayout::step_then_moments   "<prefix>t", then "<prefix>m/<i>" for every i,
//                                                  then "<prefix>v/<i>" (the first-order policy's;
//                                                  the moments only once t > 0).
// Every decoder checks sizes and that t is a non-negative integer and changes nothing on failure.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "algos/core/algorithm.h"
#include "common/adam.h"
#include "common/binary_io.h"

namespace bsg::algos {

void save_adam_state(const Adam& adam, BinaryWriter& writer);
// Fails on the reader, naming `owner` ("value net Adam first moment: ..."), on a size that is not
// the optimiser's or a negative step count.
void load_adam_state(Adam& adam, BinaryReader& reader, const std::string& owner);

enum class AdamEntryLayout { moments_then_step, step_then_moments };

std::vector<NamedScalar> adam_state_entries(const Adam& adam, std::string_view prefix, AdamEntryLayout layout);
// The number of parameters a saved step_then_moments state holds (0 when t = 0). Throws
// std::invalid_argument naming the entry at fault when `saved` is not such a state.
Eigen::Index saved_adam_parameters(std::span<const NamedScalar> saved, std::string_view prefix);
// Restores `adam` from entries of `layout` whose sizes match it. Throws std::invalid_argument naming
// the entry at fault (a name, a step count that is not a non-negative integer, a count of entries).
void restore_adam_state_entries(Adam& adam, std::span<const NamedScalar> saved, std::string_view prefix,
                                AdamEntryLayout layout);

}  // namespace bsg::algos
