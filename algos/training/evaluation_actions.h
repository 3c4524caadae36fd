// How the evaluation acts (docs/reproducing.md#evaluation): with the policy's
// mean, as the report does, or sampling a = mu + sigma eps (sampled_evaluation).
#pragma once

namespace bsg::algos {

enum class EvaluationActions { mean, sampled };

}  // namespace bsg::algos
