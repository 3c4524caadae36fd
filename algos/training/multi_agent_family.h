// The multi-agent family (docs/multi_agent.md#learners): MAPPO, MAPPO-L, HAPPO and MACPO (alg mappo,
// mappo-lag, happo, macpo) on the multi-agent environments (envs/multi_agent_env.h). Per epoch k, on every rank:
//   1. collect N = B / R team steps (multi_agent_rollout.h): each agent's action from its slot's
//      actor, V(s) and V_C(s) from its slot's centralised critics, GAE per agent in its own buffer;
//   2. pool the team's episodes over ranks: an episode's return and cost are the agents' mean
//      (SafePO's Metrics/EpRet and EpCost, the mean over agents of each agent's sum); J_C, their
//      mean over the epoch's completed episodes, is what MAPPO-L constrains against cost_limit
//      (the per-agent d of the environment, docs/multi_agent.md#ids);
//   3. per slot (one per agent, or one shared): its agents' rows stacked, the advantages (and cost
//      advantages) standardised over them as SafePO's trainers do, and PPO's clipped update
//      (algos/first_order/ppo.h) with the slot's own Adam; MAPPO-L's slot first steps its multiplier
//      on J_C - d and then takes A_hat = (A - lambda A^C) / (1 + lambda) (PPO-Lag's update, see
//      below for SafePO's differences);
//      HAPPO and MACPO (is_sequential_multi_agent: one slot per agent) replace step 3 with one
//      sequential round (algos/multi_agent/sequential_round.h): each agent's AgentBatch from its own
//      buffer, its advantages standardised over its rows, the order sequential_agent_order(n, seed,
//      k); HAPPO's agent steps with its own Ppo (its Adam state in the checkpoint), MACPO's takes
//      CPO's step with c_i = macpo_constraint_violation(J_C of agent i, cost_limit, gamma);
//   4. fit every slot's V and V_C on the stacked critic inputs (value_function.h schedule);
//   5. update the observation and state normalisers, check parameters (and the ranks' agreement).
//
// Differences from SafePO's mappolag.py, all of bsg's existing kind: the multiplier is a
// LagrangeMultiplier (algos/lagrange, lambda_optimizer SGD by default: lambda <- max(0, lambda +
// lambda_lr (J_C - d)) once per epoch on this epoch's episodes, where SafePO steps every minibatch
// by lagrangian_coef_rate ((1 - gamma)(J_C - d) + mean rho A^C) on the last epoch's, whose second
// term starts at 0 with standardised A^C); the Lagrangian advantage is divided by 1 + lambda; the
// critics fit a squared error without PopArt, clipping or Huber loss.
//
// Seeding as the on-policy family (on_policy_family.h): network init (network_init, 0, 0) and a
// broadcast from rank 0; environment (environment, rank, k); action noise (action_noise, rank, k);
// shuffles (minibatch_shuffle, rank, k); evaluation (evaluation_environment, rank, 0). A run resumed
// from the checkpoint after epoch k reproduces the uninterrupted run exactly.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/epoch_statistics.h"
#include "algos/core/value_function.h"
#include "algos/multi_agent/multi_agent_networks.h"
#include "algos/multi_agent/sequential_round.h"
#include "algos/training/multi_agent_rollout.h"
#include "algos/training/training_family.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"
#include "envs/multi_agent_env.h"

namespace bsg::algos {

// The team's episodes of this rank: each completed episode's return and cost as the mean over
// agents of the agents' own sums, and its length. Throws std::invalid_argument if the agents'
// buffers hold different episodes.
struct TeamEpisodes {
  Eigen::VectorXd returns;
  Eigen::VectorXd costs;
  Eigen::VectorXd lengths;
};
TeamEpisodes team_episodes(const MultiAgentRollout& rollout);

// The configuration of one slot's inner PPO update: alg ppo (mappo) or ppo-lag (mappo-lag), the
// log sigma learned, no KL early stop (SafePO's MAPPO trainers have none).
RunConfig slot_update_config(const RunConfig& config);

class MultiAgentFamily final : public TrainingFamily {
 public:
  MultiAgentFamily(const RunConfig& config, const MpiContext& mpi, std::unique_ptr<envs::MultiAgentEnv> env);
  ~MultiAgentFamily() override;

  std::string_view epoch_phases() const override { return "the epoch's multi-agent rollout, updates or value fits"; }
  bool checkpoints_after(int epoch) const override { return epoch % config_.save_freq == 0; }
  void start_new_run() override { networks_->broadcast_from_root(mpi_); }
  TrainingProgress load_checkpoint(const std::filesystem::path& path) override;
  void save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) override;
  FamilyEpoch run_epoch(int epoch, bool checkpoint_follows) override;
  std::vector<NamedScalar> progress_row(const EpochAccounts& accounts) override;
  std::vector<std::string> progress_columns() const override;
  EvaluationSummary evaluate(int epochs_completed) override;
  // The final evaluation (every agent's mean action; the team's return and cost the agents' mean,
  // each agent's own beside them) on `total_episodes` episodes seeded from `run_seed`: evaluate's
  // with the config's eval_episodes and seed, `bsg eval`'s with its own. Collective.
  EvaluationSummary evaluate_mean_actions(int total_episodes, std::int64_t run_seed);

  const MultiAgentNetworks& networks() const { return *networks_; }
  const OnPolicyAlgorithm& slot_algorithm(int slot) const { return *algorithms_.at(static_cast<std::size_t>(slot)); }

 private:
  // What an epoch leaves for its row.
  struct EpochRecord {
    PooledStatistics team_return, team_cost, team_length;
    std::vector<double> agent_returns, agent_costs;  // each agent's mean episode sums, pooled
    std::vector<PolicyUpdateResult> updates;         // per slot (HAPPO, MACPO: per agent)
    std::vector<AgentRoundStatistics> round;         // HAPPO, MACPO: per agent, in agent order
    std::vector<double> constraint_violations;       // MACPO: c per agent
    std::vector<std::vector<ValueFitStats>> fits;    // per slot: V, then V_C
    double collect_seconds = 0.0;
    double update_seconds = 0.0;
  };

  void pool_episodes(EpochRecord& record) const;
  void update_slot(int slot, const ConstraintEstimate& constraint, double mean_length, EpochRecord& record);
  void update_agents_in_turn(int epoch, EpochRecord& record);
  void fit_critics(int slot, EpochRecord& record);
  void update_normalizers();
  void check_parameters_finite(int epoch) const;
  std::vector<NamedScalar> log_entries(const EpochAccounts* accounts) const;

  RunConfig config_;
  MpiContext mpi_;
  std::unique_ptr<envs::MultiAgentEnv> env_;
  std::unique_ptr<MultiAgentNetworks> networks_;
  std::vector<std::unique_ptr<OnPolicyAlgorithm>> algorithms_;  // one per slot
  MultiAgentRollout rollout_;
  Rng noise_rng_;
  Rng shuffle_rng_;
  EpochRecord last_;
};

// Loads a multi-agent checkpoint into `networks` and the slots' `algorithms`; returns the progress.
TrainingProgress load_multi_agent_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                             MultiAgentNetworks& networks,
                                             std::vector<std::unique_ptr<OnPolicyAlgorithm>>& algorithms);

}  // namespace bsg::algos
