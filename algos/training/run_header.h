// The run header both checkpoint formats open with (training_checkpoint.h, off_policy_checkpoint.h):
// the resolved config as YAML (must equal the run directory's config.yaml), the rank count, the
// epochs completed, the training seconds so far and the progress.csv text of those epochs. The two
// formats have always laid it out differently, and each layout is kept byte for byte:
//   RunHeaderLayout::on_policy   section "run": config, ranks; section "progress": epochs,
//                                seconds, progress log (format 2 on)
//   RunHeaderLayout::off_policy  section "off-policy run": the marker "off-policy", config, ranks,
//                                epochs, seconds, progress log
//   RunHeaderLayout::offline     as off_policy, with section "offline run" and the marker "offline"
//   RunHeaderLayout::multi_agent as off_policy, with section "multi-agent run" and the marker "multi-agent"
// What follows the header is each format's own.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "algos/training/training_cost.h"
#include "common/binary_io.h"
#include "common/run_config.h"

namespace bsg::algos {

struct TrainingProgress {
  int epochs_completed = 0;      // epochs 0 .. epochs_completed - 1 are done
  double elapsed_seconds = 0.0;  // training wall time so far (progress.csv time_s)
  int num_ranks = 1;             // MPI ranks of the run that wrote the checkpoint
  // progress.csv of epochs 0 .. epochs_completed - 1 (none from a format 1 file).
  std::optional<std::string> progress_log;
  TrainingCost training_cost{};  // safety during training so far
};

// Bounds a loaded checkpoint's fields must lie in.
inline constexpr int kMaxCheckpointRanks = 1 << 20;

enum class RunHeaderLayout { on_policy, off_policy, offline, multi_agent };

void write_run_header(BinaryWriter& writer, RunHeaderLayout layout, const RunConfig& config,
                      const TrainingProgress& progress);

// The header's fields (training_cost left at its default). Fails on the reader, naming the field,
// if the file is not of `layout`, was written for another configuration, or holds a rank count
// outside [1, kMaxCheckpointRanks], epochs outside [0, config.epochs] or a negative or non-finite
// time. An on-policy file of format 1 has no progress log.
TrainingProgress read_run_header(BinaryReader& reader, RunHeaderLayout layout, const RunConfig& config,
                                 std::uint32_t format_version);

}  // namespace bsg::algos
