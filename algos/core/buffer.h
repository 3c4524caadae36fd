// The per-rank rollout buffer with GAE for reward and cost (docs/algorithms.md#buffer-and-gae).
// It holds exactly `capacity` = N steps per epoch; paths (episode pieces) are
// closed with finish_path(), which computes advantages, value targets and the
// discounted returns G_t that feed the return normaliser.
//
// Parameters:
//   capacity          N, local steps per epoch
//   observation_size  d_o (raw observations are stored; double instead of the
//                     original's float32)
//   action_size       d_a (unclipped actions)
//   gamma             0.99, discount for rewards AND costs
//   lam               0.95, GAE lambda for rewards
//   lam_c             0.95, GAE lambda for costs
//   consistent_return_statistic  false (Q5 kept): G_t ends in V's scaled bootstrap
//                     value; true: in V (s_ret + 1e-5), the raw units of the rewards
//   constraint_count  m, the number of constraints (docs/algorithms.md#several-constraints):
//                     each has its own cost column c_i,t, cost values, GAE
//                     advantages and targets; m = 1 (the default) is the
//                     single constraint on the environment's cost
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace bsg::algos {

struct BufferOptions {
  double gamma = 0.99;
  double lam = 0.95;
  double lam_c = 0.95;
  int constraint_count = 1;
  bool consistent_return_statistic = false;  // Q5
};

// One completed episode, raw (unscaled, undiscounted) sums.
struct EpisodeStats {
  double episode_return = 0.0;  // EpRet
  double episode_cost = 0.0;    // EpCosts: the environment's cost
  int episode_length = 0;       // EpLen
  std::vector<double> constraint_costs{};  // J_Ci of this episode, one per constraint (m = 1: episode_cost)
  // With a budget decorator (shape_last_reward): the learner's return and whether it spent a budget.
  double learner_return = 0.0;
  bool budget_spent = false;
};

// How a path ended: a finished episode (terminal or time-out; its statistics
// are recorded) or a cut at the epoch end (data only, no EpRet entry).
enum class PathEnd { episode_end, epoch_cut };

class Buffer {
 public:
  static constexpr double kRewardClip = 10.0;
  static constexpr double kStdEpsilon = 1e-5;

  Buffer(Eigen::Index capacity, int observation_size, int action_size, BufferOptions options = {});

  // Empties the buffer for a new epoch (no reallocation) and forgets the episode statistics.
  void reset();

  // Appends step t: raw observation, unclipped action, raw reward and cost,
  // V(s_t), V_C(s_t) and log pi(a_t|s_t). Throws when full or on size mismatch.
  // With one constraint only: its cost is the environment's.
  void store(const Eigen::Ref<const Eigen::VectorXd>& observation, const Eigen::Ref<const Eigen::VectorXd>& action,
             double reward, double cost, double value, double cost_value, double log_prob);
  // Any m: the environment's cost, then the m constraint costs c_i,t and values V_Ci(s_t).
  void store(const Eigen::Ref<const Eigen::VectorXd>& observation, const Eigen::Ref<const Eigen::VectorXd>& action,
             double reward, double cost, const Eigen::Ref<const Eigen::VectorXd>& constraint_costs, double value,
             const Eigen::Ref<const Eigen::VectorXd>& cost_values, double log_prob);

  // A budget decorator's step (envs/env_types.h, LearnerSignal): the learner's reward replaces
  // the environment's of the step just stored in GAE, the value targets and G_t; the episode's
  // statistics keep the environment's return and add the learner's. Throws if nothing is stored.
  void shape_last_reward(double learner_reward, bool budget_spent);

  // Closes the current path with bootstrap values (v_last, c_last) (0, 0 on a
  // true terminal). If `reward_scale_std` is set, rewards are scaled as
  // clip(r / (s_ret + 1e-5), -10, 10) for GAE and the value targets (docs/algorithms.md#reward-scaling);
  // G_t always uses raw rewards, with v_last appended (Q5) or, with
  // consistent_return_statistic and reward scaling, v_last (s_ret + 1e-5). Records the episode
  // if `end` is episode_end.
  void finish_path(double last_value, double last_cost_value, std::optional<double> reward_scale_std,
                   PathEnd end);
  // The same with one bootstrap cost value per constraint.
  void finish_path(double last_value, const Eigen::Ref<const Eigen::VectorXd>& last_cost_values,
                   std::optional<double> reward_scale_std, PathEnd end);

  Eigen::Index capacity() const { return observations_.rows(); }
  Eigen::Index size() const { return size_; }
  bool full() const { return size_ == capacity(); }
  // Length of the open (not yet finished) path.
  Eigen::Index current_path_length() const { return size_ - path_start_; }
  // Raw return, cost and length accumulated in the open path.
  const EpisodeStats& current_episode() const { return current_episode_; }
  const std::vector<EpisodeStats>& episodes() const { return episodes_; }

  // Epoch data; check_ready() throws unless the buffer is full and every path is finished.
  void check_ready() const;
  const Eigen::MatrixXd& observations() const { return observations_; }    // N x d_o, raw
  const Eigen::MatrixXd& actions() const { return actions_; }              // N x d_a
  const Eigen::VectorXd& rewards() const { return rewards_; }              // raw r_t
  const Eigen::VectorXd& values() const { return values_; }                // V_t
  const Eigen::VectorXd& log_probs() const { return log_probs_; }          // log pi_old
  const Eigen::VectorXi& episode_steps() const { return episode_steps_; }  // t within its episode (0 at a reset)
  const Eigen::VectorXd& advantages() const { return advantages_; }        // A_t
  const Eigen::VectorXd& value_targets() const { return value_targets_; }      // R_t = A_t + V_t
  const Eigen::VectorXd& discounted_returns() const { return discounted_returns_; }  // G_t
  // Per constraint: N x m, column i for constraint i.
  int constraint_count() const { return static_cast<int>(costs_.cols()); }
  const Eigen::MatrixXd& constraint_costs() const { return costs_; }                    // raw c_i,t
  const Eigen::MatrixXd& constraint_cost_values() const { return cost_values_; }        // V_Ci,t
  const Eigen::MatrixXd& constraint_cost_advantages() const { return cost_advantages_; }  // A^Ci_t
  const Eigen::MatrixXd& constraint_cost_value_targets() const { return cost_value_targets_; }  // R^Ci_t
  // Constraint 0's columns (the only ones with m = 1).
  Eigen::MatrixXd::ConstColXpr costs() const { return costs_.col(0); }                        // raw c_t
  Eigen::MatrixXd::ConstColXpr cost_values() const { return cost_values_.col(0); }            // V_C,t
  Eigen::MatrixXd::ConstColXpr cost_advantages() const { return cost_advantages_.col(0); }    // A^C_t
  Eigen::MatrixXd::ConstColXpr cost_value_targets() const { return cost_value_targets_.col(0); }  // R^C_t
  // The environment's cost summed over every step stored this epoch (complete
  // episodes or not), and each constraint's likewise: the training cost.
  double epoch_cost() const { return epoch_cost_; }
  const Eigen::VectorXd& epoch_constraint_costs() const { return epoch_constraint_costs_; }

  const BufferOptions& options() const { return options_; }

 private:
  void start_episode();  // zeroes current_episode_ (keeping its m-entry vector)
  void check_single_constraint(const char* where) const;

  BufferOptions options_;
  Eigen::MatrixXd observations_;
  Eigen::MatrixXd actions_;
  Eigen::VectorXd rewards_, values_, log_probs_;
  Eigen::VectorXi episode_steps_;
  Eigen::VectorXd advantages_, value_targets_, discounted_returns_;
  Eigen::MatrixXd costs_, cost_values_, cost_advantages_, cost_value_targets_;  // N x m
  double epoch_cost_ = 0.0;
  Eigen::VectorXd epoch_constraint_costs_;
  Eigen::Index size_ = 0;
  Eigen::Index path_start_ = 0;
  EpisodeStats current_episode_;
  std::vector<EpisodeStats> episodes_;
};

}  // namespace bsg::algos
