// libFuzzer target: the checkpoint reader (common/checkpoint_file.h and
// algos/training/training_checkpoint.h). The input is a payload, checksummed by the
// target so that the field checks behind the checksum are reached; any input
// is loaded with its fields in range or gives a CheckpointError.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "algos/core/actor_critic.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/training_checkpoint.h"
#include "common/checkpoint_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bsg::RunConfig config;
  config.alg = bsg::Algorithm::lag_trpo;
  config.use_cost_value_function = true;
  config.hidden_sizes = {4};
  config.steps_per_epoch = 400;
  bsg::Rng rng(1);
  bsg::algos::ActorCritic actor_critic(3, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  const std::string payload(reinterpret_cast<const char*>(data), size);
  try {
    const bsg::CheckpointContents contents =
        bsg::decode_checkpoint_contents(bsg::encode_checkpoint_file(payload), "fuzz.bin");
    const bsg::algos::TrainingProgress progress = bsg::algos::decode_training_checkpoint(
        contents.payload, "fuzz.bin", config, actor_critic, *algorithm, contents.format_version);
    const bool in_range = progress.num_ranks >= 1 && progress.epochs_completed >= 0 &&
                          progress.epochs_completed <= config.epochs && std::isfinite(progress.elapsed_seconds) &&
                          progress.elapsed_seconds >= 0;
    if (!in_range) __builtin_trap();
  } catch (const bsg::CheckpointError&) {
  }
  return 0;
}
