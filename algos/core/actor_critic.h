// The learner's networks and normalisers (docs/algorithms.md#networks, #normalisers): the
// Gaussian policy, the reward value net V, the cost value net V_C (always
// built and evaluated during rollouts; trained only by algorithms that use
// it), the observation normaliser and the return normaliser of reward
// scaling. Parameters are identical on every rank (broadcast at start, then
// lockstep updates), so one copy describes the whole run.
//
// Parameters (from RunConfig):
//   hidden_sizes, activation, zero_bias_init, dtype   the three MLPs (docs/algorithms.md#networks)
//   vf_lr                                 Adam learning rate of V and V_C
//   use_standardized_obs, obs_clip,       observation normalisation (docs/algorithms.md#observation-normaliser, Q3, Q4)
//   exact_parallel_variance
//   value_time_input, max_ep_len          V and V_C also see the time left (docs/algorithms.md#value-time-input)
#pragma once

#include <Eigen/Core>
#include <vector>

#include "algos/core/gaussian_policy.h"
#include "algos/core/value_function.h"
#include "common/binary_io.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"
#include "common/running_mean_std.h"

namespace bsg::algos {

struct ActorCritic {
  // Draws the initial parameters of policy, V and V_C (in that order), then
  // V_C2..V_Cm, from `init_rng`; m is the config's number of constraints.
  ActorCritic(int observation_size, int action_size, const RunConfig& config, Rng& init_rng);

  GaussianPolicy policy;
  ValueFunction value;
  ValueFunction cost_value;  // V_C, constraint 1's (the only one without `constraints:`)
  // V_C2..V_Cm of constraints 2..m (docs/algorithms.md#several-constraints), drawn
  // from `init_rng` after the three nets above; empty with one constraint, so
  // that such a run's numbers and checkpoint are those of a run before they existed.
  std::vector<ValueFunction> extra_cost_values;
  RunningMeanStd observation_normalizer;
  RunningMeanStd return_normalizer;
  bool standardize_observations = true;
  // With value_time_input, the time limit T in steps: V and every V_Ci see the
  // normalised observation and, as one more input, the fraction of the time
  // limit left, (T - t)/T at episode step t. 0: they see the observation alone.
  int value_time_limit = 0;

  int observation_size() const { return policy.observation_size(); }
  int action_size() const { return policy.action_size(); }
  int constraint_count() const { return 1 + static_cast<int>(extra_cost_values.size()); }
  // V_Ci for i = 0..m-1 (0 is cost_value).
  ValueFunction& cost_value_net(int i) { return i == 0 ? cost_value : extra_cost_values.at(static_cast<std::size_t>(i - 1)); }
  const ValueFunction& cost_value_net(int i) const {
    return i == 0 ? cost_value : extra_cost_values.at(static_cast<std::size_t>(i - 1));
  }

  // s_hat = (s - m)/(std + 1e-5) (optionally clipped), or a copy if normalisation is off.
  void normalize_observation(const Eigen::Ref<const Eigen::VectorXd>& raw,
                             Eigen::Ref<Eigen::VectorXd> normalized) const;
  void normalize_observations(const Eigen::Ref<const Eigen::MatrixXd>& raw,
                              Eigen::Ref<Eigen::MatrixXd> normalized) const;

  // The input size of V and V_Ci: d_o, or d_o + 1 with the time input.
  int value_input_size() const { return observation_size() + (value_time_limit > 0 ? 1 : 0); }
  // V's input for a normalised observation at episode step t (`input` holds
  // value_input_size() entries); the observation alone without the time input.
  void value_input(const Eigen::Ref<const Eigen::VectorXd>& normalized, int episode_step,
                   Eigen::Ref<Eigen::VectorXd> input) const;
  // The same for a batch, one observation per row.
  void value_inputs(const Eigen::Ref<const Eigen::MatrixXd>& normalized, const Eigen::Ref<const Eigen::VectorXi>& episode_steps,
                    Eigen::Ref<Eigen::MatrixXd> inputs) const;

  // Every rank takes rank 0's parameters and statistics (docs/algorithms.md#set-up, step 5).
  void broadcast_from_root(const MpiContext& mpi);

  // Sum of every parameter of the three nets (docs/algorithms.md#set-up, step 5's consistency check).
  double parameter_sum() const;
  // Name of the first non-finite quantity among the nets and normalisers, or "".
  const char* first_non_finite() const;

  // Parameters, Adam states and normaliser statistics (not sigma, which the
  // epoch sets). load() checks every size against this object's shapes.
  void save(BinaryWriter& writer) const;
  void load(BinaryReader& reader);
};

}  // namespace bsg::algos
