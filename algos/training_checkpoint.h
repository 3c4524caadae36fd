// The training checkpoint of a run directory: everything a run needs to
// continue exactly where it stopped (docs/reproducing.md#run-directory plus what resuming needs).
//
// Payload (inside common/checkpoint_file.h's container: magic, version,
// size, FNV-1a checksum), in order of named sections:
//   "run"            the resolved config as YAML (must equal the run
//                    directory's config.yaml when loading), the rank count
//   "progress"       epochs completed, training seconds so far
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

#include <filesystem>

#include "algos/actor_critic.h"
#include "algos/algorithm.h"
#include "algos/training_cost.h"
#include "common/run_config.h"

namespace bsg {

struct TrainingProgress {
  int epochs_completed = 0;      // epochs 0 .. epochs_completed - 1 are done
  double elapsed_seconds = 0.0;  // training wall time so far (progress.csv time_s)
  int num_ranks = 1;             // MPI ranks of the run that wrote the checkpoint
  TrainingCost training_cost{};  // safety during training so far
};

// The payload bytes (for tests) and the atomic write of the whole file.
std::string encode_training_checkpoint(const RunConfig& config, const TrainingProgress& progress,
                                       const ActorCritic& actor_critic, const TrustRegionAlgorithm& algorithm);
void save_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                              const TrainingProgress& progress, const ActorCritic& actor_critic,
                              const TrustRegionAlgorithm& algorithm);

// Restores `actor_critic` and `algorithm` (built from `config`) and returns
// the progress. Throws CheckpointError naming the file if it is missing,
// truncated, corrupt, from another format version, or written for a
// different configuration.
TrainingProgress load_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                          ActorCritic& actor_critic, TrustRegionAlgorithm& algorithm);
TrainingProgress decode_training_checkpoint(std::string_view payload, const std::string& source_name,
                                            const RunConfig& config, ActorCritic& actor_critic,
                                            TrustRegionAlgorithm& algorithm);

}  // namespace bsg
