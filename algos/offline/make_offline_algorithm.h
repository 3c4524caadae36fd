// The factory of the offline algorithms from a run's config: which rows of the dataset each learns
// from, and the algorithm itself. The offline family (algos/training/offline_family.h) and the loader
// of trained policies (algos/training/load_policy.h) build every offline algorithm here.
#pragma once

#include <memory>

#include "algos/offline/bcq_lag.h"
#include "algos/offline/coptidice.h"
#include "algos/offline/cpq.h"
#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "algos/offline/offline_dataset.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::algos {

// CPQ's options from a run: hidden_sizes, activation, zero_bias_init and dtype for every network;
// gamma, polyak, actor_lr, critic_lr, cost_limit, max_ep_len (T) and the offline group's CPQ keys.
CpqOptions cpq_options(const RunConfig& config);

// BCQ-Lag's options from a run, as CPQ's, with the offline group's bcq_* keys.
BcqLagOptions bcq_lag_options(const RunConfig& config);

// COptiDICE's options from a run, with the training rows' `statistics`.
COptiDiceOptions coptidice_options(const RunConfig& config, const TrainingStatistics& statistics);

// bc-all, cpq, bcq-lag and coptidice: every row; bc-safe: the episodes with cost return <= cost_limit. Throws
// std::invalid_argument if there is none, or if config.alg is not offline.
TrainingRows offline_training_rows(const RunConfig& config, const OfflineDataset& dataset);

// The algorithm of config.alg for observations and actions of these sizes, its networks drawn from
// `init_rng` (a checkpoint's state may then overwrite everything, the scaling and statistics included).
std::unique_ptr<OfflineAlgorithm> make_offline_algorithm(const RunConfig& config, int observation_size,
                                                         int action_size, const ObservationScaling& scaling,
                                                         Rng& init_rng, const TrainingStatistics& statistics = {});

}  // namespace bsg::algos
