// n-step transitions for the replay buffer (docs/algorithms.md#off-policy-learners): the steps of one
// environment's episode go in one at a time; once n are pending the oldest leaves as
//   (s_t, a_t, R = sum_{k<n} gamma^k r_{t+k}, C_i likewise, s_{t+n}, gamma^n, terminal)
// and at the episode's end every pending step leaves with the steps it has left (k < n of them,
// discount gamma^k). `terminal` is 1 only when the episode terminated (the agent died, the task
// ended) within the transition's steps: a time-limit truncation, and the cut at the end of an
// epoch, keep terminal = 0 so that the critic bootstraps from s' (design.md "a truncation
// bootstraps; a termination does not"). n = 1 gives the one-step transitions.
//
// Pending steps live in buffers sized at construction: no allocation per step.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "algos/off_policy/replay_buffer.h"

namespace bsg::algos {

class NStepAccumulator {
 public:
  // Throws std::invalid_argument for n < 1 or gamma outside (0, 1].
  NStepAccumulator(int n, double gamma, int observation_size, int action_size, int cost_count);

  // Adds the step (s, a, r, c, s'). `episode_ends`: the episode ends with this step (terminated,
  // truncated, or cut); then every pending step is written out. Completed transitions go to `buffer`.
  void add(std::span<const double> observation, std::span<const double> action, double reward,
           std::span<const double> costs, std::span<const double> next_observation, bool terminated,
           bool episode_ends, ReplayBuffer& buffer);

  // Writes every pending step out as at a truncation: bootstrapped from `next_observation`, the
  // state the episode has reached (a checkpoint taken in mid-episode, algos/training/off_policy_trainer.h).
  void flush(std::span<const double> next_observation, ReplayBuffer& buffer);

  int pending() const { return count_; }
  // Drops the pending steps (a new episode starts without writing them).
  void clear() { count_ = 0; first_ = 0; }

 private:
  // Writes the oldest pending step's transition over the `count_` pending steps, then drops it.
  void emit_oldest(std::span<const double> next_observation, bool terminal, ReplayBuffer& buffer);

  int n_;
  double gamma_;
  int first_ = 0;  // ring position of the oldest pending step
  int count_ = 0;
  std::vector<Eigen::VectorXd> observations_;
  std::vector<Eigen::VectorXd> actions_;
  std::vector<Eigen::VectorXd> costs_;
  std::vector<double> rewards_;
  Eigen::VectorXd cost_sum_;
};

}  // namespace bsg::algos
