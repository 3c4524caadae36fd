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
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace bsg {

struct BufferOptions {
  double gamma = 0.99;
  double lam = 0.95;
  double lam_c = 0.95;
};

// One completed episode, raw (unscaled, undiscounted) sums.
struct EpisodeStats {
  double episode_return = 0.0;  // EpRet
  double episode_cost = 0.0;    // EpCosts
  int episode_length = 0;       // EpLen
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
  void store(const Eigen::Ref<const Eigen::VectorXd>& observation, const Eigen::Ref<const Eigen::VectorXd>& action,
             double reward, double cost, double value, double cost_value, double log_prob);

  // Closes the current path with bootstrap values (v_last, c_last) (0, 0 on a
  // true terminal). If `reward_scale_std` is set, rewards are scaled as
  // clip(r / (s_ret + 1e-5), -10, 10) for GAE and the value targets (docs/algorithms.md#reward-scaling);
  // G_t always uses raw rewards with v_last appended (Q5). Records the episode
  // if `end` is episode_end.
  void finish_path(double last_value, double last_cost_value, std::optional<double> reward_scale_std,
                   PathEnd end);

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
  const Eigen::VectorXd& costs() const { return costs_; }                  // raw c_t
  const Eigen::VectorXd& values() const { return values_; }                // V_t
  const Eigen::VectorXd& cost_values() const { return cost_values_; }      // V_C,t
  const Eigen::VectorXd& log_probs() const { return log_probs_; }          // log pi_old
  const Eigen::VectorXd& advantages() const { return advantages_; }        // A_t
  const Eigen::VectorXd& cost_advantages() const { return cost_advantages_; }  // A^C_t
  const Eigen::VectorXd& value_targets() const { return value_targets_; }      // R_t = A_t + V_t
  const Eigen::VectorXd& cost_value_targets() const { return cost_value_targets_; }  // R^C_t
  const Eigen::VectorXd& discounted_returns() const { return discounted_returns_; }  // G_t

  const BufferOptions& options() const { return options_; }

 private:
  BufferOptions options_;
  Eigen::MatrixXd observations_;
  Eigen::MatrixXd actions_;
  Eigen::VectorXd rewards_, costs_, values_, cost_values_, log_probs_;
  Eigen::VectorXd advantages_, cost_advantages_, value_targets_, cost_value_targets_, discounted_returns_;
  Eigen::Index size_ = 0;
  Eigen::Index path_start_ = 0;
  EpisodeStats current_episode_;
  std::vector<EpisodeStats> episodes_;
};

}  // namespace bsg
