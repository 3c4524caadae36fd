// The training checkpoint of a run directory: everything a run needs to
// continue exactly where it stopped (docs/reproducing.md#run-directory plus what resuming needs).
//
// Payload (inside common/checkpoint_file.h's container: magic, version,
// size, FNV-1a checksum), in order of named sections:
//   "run", "progress"  the run header (run_header.h, its on-policy layout):
//                    the resolved config as YAML (must equal the run
//                    directory's config.yaml when loading), the rank count;
//                    epochs completed, training seconds so far, and (format
//                    2 on) the progress.csv text of those epochs: header and
//                    one row per epoch, so that a resume can tell a foreign
//                    or damaged log and restore lost rows (progress_csv.h)
//   "policy", "value net", "cost value net", "observation normaliser",
//   "return normaliser"   (ActorCritic::save: parameters, Adam moments and
//                    step counts, normaliser mean/std/count)
//   "algorithm"      the algorithm's name and its named state (lambda and
//                    its optimiser moments for TRPO-L and PDO)
//   "training cost"  the cost incurred so far (training_cost.h); a checkpoint
//                    written before it existed resumes with the sums at 0
//
// No RNG state is stored: every random stream of epoch k is seeded from
// (run seed, stream, rank, k) at the start of the epoch (trainer.h), so
// the epoch number is all the randomness a resume needs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "algos/core/actor_critic.h"
#include "algos/core/algorithm.h"
#include "common/checkpoint_file.h"
#include "algos/training/run_header.h"
#include "algos/training/training_cost.h"
#include "common/run_config.h"

namespace bsg::algos {

// The payload bytes (for tests) and the atomic write of the whole file.
std::string encode_training_checkpoint(const RunConfig& config, const TrainingProgress& progress,
                                       const ActorCritic& actor_critic, const OnPolicyAlgorithm& algorithm);
void save_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                              const TrainingProgress& progress, const ActorCritic& actor_critic,
                              const OnPolicyAlgorithm& algorithm);

// Restores `actor_critic` and `algorithm` (built from `config`) and returns
// the progress. Throws CheckpointError naming the file if it is missing (or a
// directory, a FIFO, ...), truncated, corrupt, from another format version,
// written for a different configuration, or holds a field out of range: a
// rank count outside [1, kMaxCheckpointRanks], a negative or non-finite
// elapsed time, epochs outside [0, epochs], a progress log that does not hold
// exactly those epochs' rows (with this config's step counts) or whose last
// time_s is not the elapsed time.
TrainingProgress load_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                          ActorCritic& actor_critic, OnPolicyAlgorithm& algorithm);
TrainingProgress decode_training_checkpoint(std::string_view payload, const std::string& source_name,
                                            const RunConfig& config, ActorCritic& actor_critic,
                                            OnPolicyAlgorithm& algorithm,
                                            std::uint32_t format_version = kCheckpointFormatVersion);

}  // namespace bsg::algos
