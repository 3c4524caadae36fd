// The checkpoint of an off-policy run (docs/reproducing.md#run-directory): checkpoint.bin, written by
// rank 0 inside common/checkpoint_file.h's container, holds in named sections
//   "off-policy run"   the run header (run_header.h, its off-policy layout: the marker "off-policy",
//                      the resolved config as YAML (must equal the run's), the rank count, epochs
//                      completed, training seconds, the progress.csv text of those epochs), then the
//                      training cost and the update schedule's carry
//   "multipliers"      every Lagrange multiplier's named state (none for sac, td3, ddpg)
//   "off-policy networks"  the learner (off_policy_learner.h: every net, target, Adam state, log alpha)
// with the number of transitions each rank's replay buffer had taken, whose transitions every rank r
// has appended to its record replay_buffer.r<r>.log (replay_buffer_log.h) before rank 0 writes
// checkpoint.bin: a run killed between the two resumes from the previous checkpoint, and the record's
// later transitions are cut off.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/training/run_header.h"
#include "common/run_config.h"

namespace bsg::algos {

struct OffPolicySchedule;

struct OffPolicyCheckpoint {
  TrainingProgress progress;
  long long replay_transitions = 0;  // transitions each rank's buffer had taken
  long long steps_since_update = 0;
  double owed_updates = 0.0;
  std::vector<NamedScalar> multipliers;
};

std::string encode_off_policy_checkpoint(const RunConfig& config, const OffPolicyCheckpoint& state,
                                         const OffPolicyLearner& learner);
// Restores `learner` and returns the rest. Throws CheckpointError naming the file if it is missing,
// corrupt, not an off-policy checkpoint, or written for another configuration.
OffPolicyCheckpoint load_off_policy_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                               OffPolicyLearner& learner);

}  // namespace bsg::algos
