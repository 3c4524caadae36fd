// OfflineKeys: the configuration keys of the offline family (bc-all, bc-safe;
// docs/datasets.md#offline-runs): the dataset a run learns from, its gradient
// steps per epoch and how often it is evaluated online. RunConfig holds them as
// `offline`; their rows in the key table are in offline_keys.cpp. The family
// also reads keys of other groups whose meaning it shares: actor_lr
// (FirstOrderKeys, the policy's Adam step size), batch_size (OffPolicyKeys,
// rows per gradient step), and RunConfig's hidden_sizes, activation,
// zero_bias_init, dtype, cost_limit (BC-Safe's episodes), epochs,
// eval_episodes, save_freq and seed.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml):
//   dataset = "" (required), updates_per_epoch = 200, eval_every = 1
#pragma once

#include <string>

namespace bsg {

struct OfflineKeys {
  std::string dataset;          // the HDF5 file (DSRL's layout) the policy learns from
  int updates_per_epoch = 200;  // gradient steps per epoch
  int eval_every = 1;           // online evaluation after every eval_every-th epoch (and the last)

  bool operator==(const OfflineKeys&) const = default;
};

}  // namespace bsg
