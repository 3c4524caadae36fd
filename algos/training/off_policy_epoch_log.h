// One progress.csv row per epoch of an off-policy run (docs/algorithms.md#the-off-policy-loop). The
// columns, in order (one list in off_policy_epoch_log.cpp gives the header and the row):
//   epoch, total_env_steps, episode_{return,cost,length}_{mean,std,min,max}, episodes
//   updates                 gradient steps this epoch, per rank
//   reward_critic_loss      summed over the twin critics; q_reward_mean
//   cost_critic_loss, q_cost_mean   per constraint of a -lag learner (constraint_<i>_ prefixed with several)
//   actor_loss, alpha (SAC), the multipliers' columns (lagrange_multiplier, pid_*_term)
//   constraint_<i>_cost and _limit with `constraints:`
//   time_collect_s, time_update_s, time_s, fps, cumulative_cost, cost_rate
// Losses and Q values are means over the epoch's gradient steps, averaged over ranks (NaN in an
// epoch without gradient steps).
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/training/training_cost.h"
#include "common/mpi_context.h"

namespace bsg::algos {

// What decides an off-policy run's columns.
struct OffPolicyLogLayout {
  int critic_cost_count = 0;                  // cost critics (m for the -lag learners, else 0)
  bool prefixed_cost_critics = false;         // several constraints: constraint_<i>_ before the critic columns
  bool alpha = false;                         // SAC's temperature
  std::vector<std::string> multiplier_names;  // the multipliers' diagnostics, in order
  int per_constraint = 0;                     // m with `constraints:`, else 0
};

// The episodes this rank completed in an epoch.
struct OffPolicyEpisodes {
  std::vector<double> returns, costs, lengths;
};

// The gradient steps this rank took in an epoch, summed.
struct OffPolicyUpdateTally {
  long long updates = 0;
  long long actor_updates = 0;
  double reward_critic_loss = 0.0, reward_q = 0.0, actor_loss = 0.0;
  Eigen::VectorXd cost_critic_losses, cost_qs;  // per cost critic
};

struct OffPolicyLogInputs {
  int epoch = 0;
  int steps_per_epoch = 0;
  const OffPolicyEpisodes* episodes = nullptr;
  long long episode_count = 0;  // all ranks
  const OffPolicyUpdateTally* updates = nullptr;
  double alpha = 0.0;
  std::vector<NamedScalar> multipliers;           // the multipliers' diagnostics
  std::span<const ConstraintEstimate> constraints;  // this epoch's J_Ci and d_i
  double collect_seconds = 0.0, update_seconds = 0.0, epoch_seconds = 0.0, elapsed_seconds = 0.0;
  const TrainingCost* training_cost = nullptr;  // after this epoch
};

// The columns of `layout`, in order.
std::vector<std::string> off_policy_log_columns(const OffPolicyLogLayout& layout);
// The row (collective: every rank takes part in the reductions and gets the row).
std::vector<NamedScalar> make_off_policy_log_row(const OffPolicyLogLayout& layout, const OffPolicyLogInputs& inputs,
                                                 const MpiContext& mpi);

}  // namespace bsg::algos
