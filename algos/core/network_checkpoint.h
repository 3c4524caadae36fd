// The checkpoint parts every family's networks share: a value function (its
// parameters and its Adam state) and a running normaliser (mean, std, count),
// written and read in one order, so that the on-policy actor-critic and the
// multi-agent policy slots store them alike.
#pragma once

#include <string>

#include "algos/core/value_function.h"
#include "common/binary_io.h"
#include "common/running_mean_std.h"

namespace bsg::algos {

void save_value_function(const ValueFunction& value, BinaryWriter& writer);
// `name` prefixes the reader's errors ("<name> parameters", ...).
void load_value_function(ValueFunction& value, BinaryReader& reader, const std::string& name);

void save_normalizer(const RunningMeanStd& normalizer, BinaryWriter& writer);
void load_normalizer(RunningMeanStd& normalizer, BinaryReader& reader, const std::string& name);

}  // namespace bsg::algos
