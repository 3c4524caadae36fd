// `bsg eval DIR`: re-runs the evaluation (docs/reproducing.md#evaluation) of a run directory's
// latest checkpoint, without writing anything.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "algos/training/evaluation.h"
#include "algos/training/run_directory.h"
#include "common/mpi_context.h"
#include "envs/multi_agent_env.h"

namespace bsg::algos {

struct RunEvaluation {
  EvaluationSummary summary;  // rank 0 only
  int epochs_completed = 0;   // of the checkpoint
  int epochs = 0;             // of the run's config
};

// `episodes` overrides the config's eval_episodes. Collective. Throws naming
// the directory or file at fault (not a run directory, corrupt checkpoint). A multi-agent run is
// evaluated by its family's final evaluation (MultiAgentFamily::evaluate_mean_actions: every
// agent's mean action; the summary holds each agent's return and cost beside the agents' mean).
RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi);

// The same with the environment wrapped by `decorate` before the episodes run
// (e.g. to record them: render/observed_env.h); the results are unchanged. `actions`
// overrides the config's sampled_evaluation (the sampled actions use the sigma of the
// checkpoint's last epoch); `seed` the run seed the evaluation's streams derive from
// (bsg.evaluate(seed=...): other episodes of the same policy). A multi-agent run's environment
// is wrapped by `decorate_multi_agent` instead (render/observed_multi_agent_env.h); it acts with
// its agents' mean actions only, and is refused in one line with sampled actions or with
// `decorate` but no `decorate_multi_agent` (a caller that records single-agent runs only).
using EnvDecorator = std::function<std::unique_ptr<envs::Env>(std::unique_ptr<envs::Env>)>;
using MultiAgentEnvDecorator = std::function<std::unique_ptr<envs::MultiAgentEnv>(std::unique_ptr<envs::MultiAgentEnv>)>;
RunEvaluation evaluate_run_directory(const RunDirectory& directory, std::optional<int> episodes,
                                     const MpiContext& mpi, const EnvDecorator& decorate,
                                     std::optional<EvaluationActions> actions = std::nullopt,
                                     std::optional<std::int64_t> seed = std::nullopt,
                                     const MultiAgentEnvDecorator& decorate_multi_agent = {});

// Throws std::invalid_argument in one line if `directory` holds a multi-agent run and the
// evaluation asks for sampled actions (before a caller opens its recordings). Throws as
// load_policy if `directory` holds no run.
void check_multi_agent_evaluation(const RunDirectory& directory, bool sampled_actions);

}  // namespace bsg::algos
