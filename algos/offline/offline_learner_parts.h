// What the offline learners with critics (cpq.h, bcq_lag.h, coptidice.h) build from alike: the layer
// sizes of their MLPs, their standard normal draws from the family's batch stream, and OSRL's per-step
// cost threshold.
#pragma once

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algos/offline/offline_algorithm.h"
#include "common/random.h"

namespace bsg::algos {

// {input, hidden..., output}.
std::vector<int> mlp_layers(int input, const std::vector<int>& hidden, int output);

// `noise` resized to rows x cols and filled row by row with standard normal draws from `rng`.
void fill_standard_normal(Rng& rng, Eigen::MatrixXd& noise, Eigen::Index rows, Eigen::Index cols);

// Throws std::invalid_argument naming `learner` unless `batch` has at least one row and every field the
// rows and columns of these sizes.
void check_batch_fits(const OfflineBatch& batch, int observation_size, int action_size, std::string_view learner);

// OSRL's qc_thres, the discounted cost per step of an episode of T steps within the limit d:
// l = d (1 - gamma^T) / ((1 - gamma) T), and l = d at gamma = 1 (the limit of the formula).
double per_step_cost_threshold(double cost_limit, double gamma, int episode_length);

}  // namespace bsg::algos
