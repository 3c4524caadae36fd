// How the evaluation acts (docs/reproducing.md#evaluation): with the policy's mean, as the report
// does, or sampling the actions it explores with (sampled_evaluation). The acting policy's own
// choice (algos/core/acting_policy.h), named as the configs name it.
#pragma once

#include "algos/core/acting_policy.h"

namespace bsg::algos {

using EvaluationActions = ActionMode;

}  // namespace bsg::algos
