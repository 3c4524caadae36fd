// What every way of starting a training run does before its first epoch, written once for
// `bsg train` and the Python module's `bsg.train`, so that both train the same run from the
// same configuration: the configuration resolved from its layers (with the env: block checked
// against the environment table), the checks a run must pass before it trains, and the trainer
// allocated with a message naming the estimate when memory runs out.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "algos/training/run_directory.h"
#include "algos/training/trainer.h"
#include "common/mpi_context.h"
#include "common/run_config.h"
#include "common/run_config_resolve.h"

namespace bsg::algos {

// Every id a run may train on: the single-agent registry's and the multi-agent registry's, sorted.
std::vector<std::string> training_env_ids();

// Throws ConfigError in one line if a multi-agent learner is given a single-agent env_id or a
// single-agent learner a multi-agent one, or a sequential one (happo, macpo) share_policy.
void check_env_matches_family(const RunConfig& config);

// resolve_run_config with the registered environment ids (both registries), the env: block checked, and an
// offline dataset named absolutely (config.yaml names it so, so that a resume and `bsg eval`
// work from any folder). Throws ConfigError naming the key and where its value came from.
RunConfig resolve_training_config(RunConfigRequest request);

// The configuration of the run in `directory` (its config.yaml), for a resume; throws if the
// directory holds no run.
RunConfig resumed_training_config(const RunDirectory& directory);

// Every check a run must pass before it trains (`bsg train --print-config` runs them too): the
// batch split over the ranks, the environment with its physics model, and the memory estimate
// against the memory available. Throws ConfigError.
void check_before_training(const RunConfig& config, int num_ranks);

// make_trainer; running out of memory there is reported with what was being allocated and the
// estimate (std::runtime_error).
std::unique_ptr<Trainer> allocate_trainer(const RunConfig& config, const RunDirectory& directory,
                                          const MpiContext& mpi, const TrainerOptions& options);

}  // namespace bsg::algos
