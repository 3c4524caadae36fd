// One progress.csv row per epoch (docs/algorithms.md#logged-columns, #across-mpi-ranks). The columns, in order:
//
//   epoch                   k, 0-based ("Epoch")
//   total_env_steps         (k + 1) B, summed over ranks ("TotalEnvSteps")
//   episode_return_{mean,std,min,max}   raw undiscounted return of the episodes
//                           completed this epoch, pooled over ranks ("EpRet/*")
//   episode_cost_{mean,std,min,max}     ("EpCosts/*")
//   episode_length_{mean,std,min,max}   ("EpLen/*")
//   episodes                number of completed episodes, all ranks
//   with a budget decorator (budget_decorator.h; the columns above stay the environment's):
//   learner_return_mean     the learner's own return of those episodes (Saute's penalised
//                           reward, early termination's 0 at the cut)
//   budget_spent_fraction   the fraction of those episodes that spent a budget (Saute: the
//                           reward was replaced; early termination: the episode was cut)
//   value_{mean,min,max}    V(s_t) over the batch ("Values/V/*")
//   advantage_{mean,min,max}  the reward advantages A_t (the original logs the
//                           actions under "Values/Adv", Q18; these are the true values)
//   cost_value_{mean,min,max}  V_C(s_t) ("Values/C/*")
//   value_loss, value_loss_delta   full-batch loss of V before the fit and the
//                           mean minibatch loss minus it ("Loss/Value", "Loss/DeltaValue")
//   cost_value_loss, cost_value_loss_delta   the same for V_C, only if the
//                           algorithm trains it ("Loss/Cost", "Loss/DeltaCost"; Q18)
//   exploration_std         sigma_k ("Misc/ExplorationNoiseStd")
//   reward_scale_mean, reward_scale_std   return normaliser after the update ("Misc/RewScale*")
//   then the algorithm's diagnostics (algorithm.h), renamed by
//   progress_column_name(): policy_loss, policy_loss_delta, entropy, kl,
//   policy_ratio, line_search_acceptance_step, step_alpha, final_step_norm,
//   gradient_norm, xFx, cg_solution_norm, and per algorithm
//   lagrange_multiplier, cost_gradient_norm, cpo_A, cpo_B, cpo_q, cpo_r,
//   cpo_s, cpo_lambda_star, cpo_nu_star, cpo_optim_case; with
//   lambda_optimizer PID (TRPO-L, PDO) also pid_p_term = K_P Delta_ema,
//   pid_i_term = I and pid_d_term = K_D max(0, J_ema - J_ema[k - delay])
//   after this epoch's update (lambda = max(0, their sum), pid_lagrangian.h)
//   time_collect_s, time_update_s   this epoch's seconds on rank 0
//   with `constraints:` (docs/algorithms.md#several-constraints), per constraint i = 1..m:
//   constraint_<i>_cost     J_Ci, pooled mean episode cost of constraint i this epoch
//   constraint_<i>_limit    d_i
//   constraint_<i>_cumulative_cost, constraint_<i>_cost_rate, constraint_<i>_epochs_over_limit
//                           its safety during training so far (training_cost.h)
//   constraint_<i>_cost_value_loss, constraint_<i>_cost_value_loss_delta   V_Ci's fit, as
//                           cost_value_loss (only if the algorithm trains the cost value nets)
//   (the algorithm's per-constraint multipliers come with its diagnostics:
//   constraint_<i>_lambda for TRPO-L and PDO, constraint_<i>_nu for CPO and PCPO)
//   time_s                  seconds of training since the run started (resumes continue it)
//   fps                     B / seconds of this epoch
//   cumulative_cost         the environment's cost over every training step so far, all ranks
//   cost_rate               cumulative_cost / total_env_steps (Safety Gym's cost rate)
//
// Rank-local quantities (losses, the common diagnostics) are averaged over
// ranks; the original's constant columns Misc/Seed, Misc/StopIter and LR are
// left out (the seed is in config.yaml).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/buffer.h"
#include "algos/core/epoch_statistics.h"
#include "algos/training/training_cost.h"
#include "algos/core/value_function.h"
#include "common/mpi_context.h"
#include "common/running_mean_std.h"

namespace bsg::algos {

// Episode statistics of one epoch, pooled over ranks (needed before the
// update: J_C and L feed the algorithms).
struct EpisodeStatistics {
  PooledStatistics episode_return;
  PooledStatistics episode_cost;
  PooledStatistics episode_length;
  // J_Ci of every constraint; only when `per_constraint` was asked (with
  // `constraints:`; without, the one constraint's J_C is episode_cost).
  std::vector<PooledStatistics> constraint_costs{};
  // The learner's return and the budget-spent flags (1 or 0); only when `learner_signal` was asked.
  std::optional<PooledStatistics> learner_return{};
  std::optional<PooledStatistics> budget_spent{};
};
EpisodeStatistics pool_episode_statistics(const Buffer& buffer, const MpiContext& mpi, bool per_constraint = false,
                                          bool learner_signal = false);

struct EpochLogInputs {
  int epoch = 0;
  long long total_env_steps = 0;
  int steps_per_epoch = 0;
  double exploration_std = 0.0;
  const EpisodeStatistics* episodes = nullptr;
  const Buffer* buffer = nullptr;
  const PolicyUpdateResult* update = nullptr;
  const ValueFitStats* value_fit = nullptr;
  const ValueFitStats* cost_value_fit = nullptr;  // null if V_C is not trained
  const RunningMeanStd* return_normalizer = nullptr;
  // The per-constraint columns, only with `constraints:` (empty: none).
  std::span<const ConstraintEstimate> constraints{};
  // V_Ci's fits in the constraints' order, when the algorithm trains them (empty: no loss columns).
  std::span<const ValueFitStats> constraint_cost_value_fits{};
  const TrainingCost* training_cost = nullptr;  // after this epoch; null: no safety columns
  double collect_seconds = 0.0;
  double update_seconds = 0.0;
  double elapsed_seconds = 0.0;
};

// Collective (every rank takes part in the reductions); every rank gets the row.
// Its columns are epoch_log_columns() of the layout its inputs make: one list
// in epoch_log.cpp gives both.
std::vector<NamedScalar> make_epoch_log_row(const EpochLogInputs& inputs, const MpiContext& mpi);

// What decides a run's progress.csv columns.
struct EpochLogLayout {
  bool cost_value_loss = false;               // the algorithm trains V_C
  std::vector<std::string> diagnostic_names;  // the algorithm's, in order
  int per_constraint = 0;                     // m with `constraints:`, else 0
  bool constraint_cost_value_losses = false;  // per-constraint V_Ci losses (with `constraints:` and V_C)
  bool training_cost = true;                  // the trailing safety columns (every trainer run)
  bool learner_signal = false;                // a budget decorator's columns
};
// The columns of make_epoch_log_row for that layout, in order; a checkpoint's
// progress log must have exactly these (training_checkpoint.cpp).
std::vector<std::string> epoch_log_columns(const EpochLogLayout& layout);
// The layout of a trainer run of `config` with `algorithm`.
EpochLogLayout epoch_log_layout(const RunConfig& config, const OnPolicyAlgorithm& algorithm);

// The progress.csv column of an algorithm diagnostic ("Loss/Pi" -> "policy_loss", ...);
// unknown names are lower-cased with '/' turned into '_'.
std::string progress_column_name(std::string_view diagnostic_name);

// True for the columns that hold wall-clock measurements (time_*, fps): the
// only ones in which two runs with the same seed may differ.
bool is_timing_column(std::string_view column);

}  // namespace bsg::algos
