// The policy of a trained run, read from its run directory's checkpoint, as a
// CollectionPolicy. An on-policy run: the observation normalised with the
// checkpoint's frozen statistics, then the mean action, or a sample
// mu + sigma eps at the sigma of the checkpoint's last epoch (the evaluation's
// two modes, evaluation.h). An off-policy run (SAC, TD3, DDPG and their -lag
// forms): the deterministic actor tanh(mu(s)) for mean actions, the exploring
// actions it collected with for sampled ones.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "algos/offline/collection_policy.h"
#include "algos/training/evaluation_actions.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

class CheckpointPolicy : public CollectionPolicy {
 public:
  // The run's resolved configuration and environment description, for checks
  // against the environment of a collection.
  virtual const RunConfig& config() const = 0;
  virtual const envs::EnvDescription& env_description() const = 0;
};

// Throws naming the directory or file at fault (not a run directory, corrupt checkpoint).
// `name`, when not empty, is how description() names the run directory (e.g.
// relative to a dataset's folder); errors always name the path itself.
std::unique_ptr<CheckpointPolicy> load_checkpoint_policy(const std::filesystem::path& run_directory,
                                                         EvaluationActions actions, const std::string& name = "");

}  // namespace bsg::algos
