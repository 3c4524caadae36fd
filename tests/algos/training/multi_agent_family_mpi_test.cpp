// The multi-agent family under `mpirun -np 2`.
// - Training: each rank collects its half of the team steps, the gradients are averaged, and every
//   rank ends with identical actors, critics, Adam states and multipliers (MAPPO-L, HAPPO, MACPO);
//   rank 0 gathers both ranks' evaluation episodes.
// - One rank equals two: HAPPO's and MACPO's policy step of an epoch (sequential_policy_step: the
//   per-agent standardisation over ranks, MACPO's c on the team's J_C, the round) on a fixed batch
//   split in two halves over the ranks lands where one process lands on the whole batch.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "algos/core/epoch_statistics.h"
#include "algos/first_order/make_first_order_algorithm.h"
#include "algos/multi_agent/sequential_policy_step.h"
#include "algos/training/multi_agent_trainer.h"
#include "algos/training/run_start.h"
#include "common/mpi_context.h"

namespace fs = std::filesystem;

namespace {

bool same_on_all_ranks(const Eigen::VectorXd& local, const bsg::MpiContext& mpi) {
  Eigen::VectorXd root = local;
  mpi.broadcast_from_root(root);
  const double differs = (root.array() != local.array()).any() ? 1.0 : 0.0;
  return mpi.max(differs) == 0.0;
}

Eigen::VectorXd concatenated(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

std::vector<double> update_state(const bsg::algos::OnPolicyAlgorithm& algorithm) {
  std::vector<double> values;
  for (const bsg::algos::NamedScalar& entry : algorithm.state()) values.push_back(entry.value);
  return values;
}

// Every slot's actor, critics (with their Adam moments) and its update's state: PPO's Adam and
// MAPPO-L's multiplier (MACPO keeps no update state).
Eigen::VectorXd everything(const bsg::algos::MultiAgentFamily& family, bsg::Algorithm alg) {
  std::vector<double> values;
  const auto append = [&](const Eigen::VectorXd& v) { values.insert(values.end(), v.data(), v.data() + v.size()); };
  const bsg::algos::MultiAgentNetworks& networks = family.networks();
  for (int s = 0; s < networks.slot_count(); ++s) {
    const bsg::algos::AgentSlot& slot = networks.slot(s);
    append(slot.policy.mean_net().parameters());
    append(slot.policy.log_stds());
    append(slot.value.net().parameters());
    append(slot.value.optimizer().second_moment());
    if (slot.cost_value) {
      append(slot.cost_value->net().parameters());
      append(slot.cost_value->optimizer().second_moment());
    }
    if (alg != bsg::Algorithm::macpo) {
      for (const double value : update_state(family.slot_algorithm(s))) values.push_back(value);
    }
  }
  return concatenated(values);
}

bsg::RunConfig family_config(std::vector<std::string> set_arguments) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle2-v0", "hidden_sizes=[8]"};
  request.set_arguments.insert(request.set_arguments.end(), set_arguments.begin(), set_arguments.end());
  return bsg::algos::resolve_training_config(request);
}

// Trains `config` on both ranks and checks that they end alike.
void expect_ranks_end_alike(const bsg::RunConfig& config) {
  const bsg::MpiContext mpi = bsg::MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  std::string directory;
  if (mpi.is_root()) {
    char pattern[] = "/tmp/bsg_multi_agent_mpi_test_XXXXXX";
    directory = mkdtemp(pattern);
  }
  bsg::algos::MultiAgentTrainer trainer(config, bsg::algos::RunDirectory(fs::path(directory) / "run"), mpi, {});
  const bsg::algos::TrainingOutcome outcome = trainer.run();
  EXPECT_TRUE(outcome.finished);
  EXPECT_TRUE(same_on_all_ranks(everything(trainer.multi_agent(), config.alg), mpi));
  if (mpi.is_root()) {
    ASSERT_TRUE(outcome.evaluation.has_value());
    EXPECT_EQ(outcome.evaluation->episodes.size(), static_cast<std::size_t>(config.eval_episodes));  // gathered
    std::error_code ignored;
    fs::remove_all(directory, ignored);
  }
}

}  // namespace

TEST(MultiAgentFamilyMpi, RanksEndWithIdenticalNetworksAndMultipliers) {
  expect_ranks_end_alike(family_config({"alg=mappo-lag", "epochs=2", "steps_per_epoch=400", "max_ep_len=100",
                                        "eval_episodes=4", "check_freq=1", "policy_minibatch_size=200",
                                        "lambda_lr=0.01", "cost_limit=0"}));
}

TEST(MultiAgentFamilyMpi, HappoRanksEndWithIdenticalActorsCriticsAndAdamStates) {
  expect_ranks_end_alike(family_config({"alg=happo", "epochs=2", "steps_per_epoch=400", "max_ep_len=100",
                                        "eval_episodes=4", "check_freq=1", "policy_minibatch_size=200"}));
}

TEST(MultiAgentFamilyMpi, MacpoRanksEndWithIdenticalActorsAndCritics) {
  expect_ranks_end_alike(family_config({"alg=macpo", "epochs=2", "steps_per_epoch=400", "max_ep_len=100",
                                        "eval_episodes=4", "check_freq=1", "cost_limit=0"}));
}

namespace {

using bsg::algos::AgentBatch;

constexpr Eigen::Index kRows = 64;  // joint steps of the whole batch; each rank holds 32
constexpr int kAgents = 2;

// A fixed two-agent batch from fixed seeds: observations, the actions each agent's policy sampled
// and their log-probabilities, and advantages as GAE leaves them (not standardised). The first
// half's advantages are shifted and scaled against the second's, so that statistics taken per
// rank instead of over both ranks would standardise them differently.
std::vector<AgentBatch> fixed_batches(bsg::algos::MultiAgentNetworks& networks) {
  std::vector<AgentBatch> batches;
  bsg::MlpSampleWorkspace workspace;
  for (int k = 0; k < kAgents; ++k) {
    bsg::algos::GaussianPolicy& policy = networks.slot_of_agent(k).policy;
    bsg::Rng rng(900 + static_cast<std::uint64_t>(k));
    AgentBatch batch{Eigen::MatrixXd(kRows, policy.observation_size()), Eigen::MatrixXd(kRows, policy.action_size()),
                     Eigen::VectorXd(kRows), Eigen::VectorXd(kRows), Eigen::VectorXd(kRows)};
    Eigen::VectorXd action(policy.action_size());
    for (Eigen::Index i = 0; i < kRows; ++i) {
      for (Eigen::Index j = 0; j < batch.observations.cols(); ++j) batch.observations(i, j) = bsg::standard_normal(rng);
      batch.old_log_probs[i] = policy.sample_action(batch.observations.row(i).transpose(), action, rng, workspace);
      batch.actions.row(i) = action.transpose();
      const bool first_half = i < kRows / 2;
      batch.advantages[i] = (first_half ? 2.0 : -1.0) + (first_half ? 3.0 : 0.5) * bsg::standard_normal(rng);
      batch.cost_advantages[i] = (first_half ? 1.5 : -0.5) + bsg::standard_normal(rng);
    }
    batches.push_back(std::move(batch));
  }
  return batches;
}

AgentBatch rows_of(const AgentBatch& whole, Eigen::Index first, Eigen::Index count) {
  return {whole.observations.middleRows(first, count), whole.actions.middleRows(first, count),
          whole.old_log_probs.segment(first, count), whole.advantages.segment(first, count),
          whole.cost_advantages.segment(first, count)};
}

// One side of the comparison: the networks (from the same seed on both sides) and HAPPO's Ppo per agent.
struct Learner {
  std::unique_ptr<bsg::algos::MultiAgentNetworks> networks;
  std::vector<std::unique_ptr<bsg::algos::OnPolicyAlgorithm>> ppo_updates;

  explicit Learner(const bsg::RunConfig& config) {
    bsg::Rng init_rng(31);
    networks = std::make_unique<bsg::algos::MultiAgentNetworks>(bsg::algos::MultiAgentSizes{{3, 3}, {2, 2}, 6}, config,
                                                                config.alg == bsg::Algorithm::macpo, init_rng);
    if (config.alg == bsg::Algorithm::happo) {
      for (int k = 0; k < kAgents; ++k) {
        ppo_updates.push_back(bsg::algos::make_first_order_algorithm(bsg::algos::slot_update_config(config)));
      }
    }
  }
  std::vector<bsg::algos::GaussianPolicy*> policies() {
    std::vector<bsg::algos::GaussianPolicy*> pointers;
    for (int k = 0; k < kAgents; ++k) pointers.push_back(&networks->slot_of_agent(k).policy);
    return pointers;
  }
  std::vector<bsg::algos::Ppo*> ppos() {
    std::vector<bsg::algos::Ppo*> pointers;
    for (const auto& update : ppo_updates) pointers.push_back(dynamic_cast<bsg::algos::Ppo*>(update.get()));
    return pointers;
  }
  Eigen::VectorXd actor(int k) {
    const bsg::algos::GaussianPolicy& policy = networks->slot_of_agent(k).policy;
    Eigen::VectorXd parameters(policy.mean_net().parameters().size() + policy.log_stds().size());
    parameters << policy.mean_net().parameters(), policy.log_stds();
    return parameters;
  }
};

// The halves' step against the whole's. The reductions are not bit for bit: a rank's partial sums
// over its 32 rows, then the sum over ranks, round differently from one sum over 64 rows (and the
// minibatch rows come in each rank's own shuffled order), so the comparison is to 1e-12 of the
// parameters' change, in float64 arithmetic (dtype float32 rounds every batch pass to 1e-7).
void expect_halves_take_the_whole_step(const bsg::RunConfig& config) {
  const bsg::MpiContext mpi = bsg::MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  Learner on_halves(config), on_whole(config), before(config);
  const std::vector<AgentBatch> whole_batches = fixed_batches(*before.networks);
  std::vector<AgentBatch> halves;
  for (const AgentBatch& whole : whole_batches) halves.push_back(rows_of(whole, mpi.rank() * kRows / 2, kRows / 2));
  // The halves' advantages differ in mean and spread: a per-rank standardisation would show.
  const double local_mean = halves[0].advantages.mean();
  EXPECT_GT(mpi.max(local_mean) - mpi.min(local_mean), 2.0);

  // The team's episode costs, three episodes ended on rank 0 and two on rank 1: J_C is their mean
  // over all five (27), as the family pools them (pool_episodes), not the mean of the ranks' means.
  const Eigen::VectorXd local_costs =
      mpi.rank() == 0 ? Eigen::VectorXd(Eigen::Vector3d(30.0, 10.0, 40.0)) : Eigen::VectorXd(Eigen::Vector2d(20.0, 35.0));
  Eigen::VectorXd all_costs(5);
  all_costs << 30.0, 10.0, 40.0, 20.0, 35.0;
  const double halves_j_c = bsg::algos::pool_statistics(local_costs, mpi).mean;
  const double whole_j_c = bsg::algos::pool_statistics(all_costs, bsg::MpiContext::single_process()).mean;
  EXPECT_EQ(halves_j_c, 27.0);

  const std::vector<int> order{1, 0};
  bsg::Rng halves_rng(70 + static_cast<std::uint64_t>(mpi.rank()));  // each rank its own shuffles, as the family's
  bsg::Rng whole_rng(70);
  const bsg::algos::SequentialPolicyStep halves_step = bsg::algos::sequential_policy_step(
      config, halves, on_halves.policies(), on_halves.ppos(), halves_j_c, order, mpi, halves_rng);
  const bsg::algos::SequentialPolicyStep whole_step =
      bsg::algos::sequential_policy_step(config, whole_batches, on_whole.policies(), on_whole.ppos(), whole_j_c,
                                         order, bsg::MpiContext::single_process(), whole_rng);

  EXPECT_EQ(halves_step.constraint_violations, whole_step.constraint_violations);
  int moved = 0;
  for (int k = 0; k < kAgents; ++k) {
    const Eigen::VectorXd change = on_whole.actor(k) - before.actor(k);
    EXPECT_LE((on_halves.actor(k) - on_whole.actor(k)).norm(), 1e-12 * change.norm()) << "agent " << k;
    EXPECT_TRUE(same_on_all_ranks(on_halves.actor(k), mpi)) << "agent " << k;
    moved += change.norm() > 0.0 ? 1 : 0;
    const bsg::algos::AgentRoundStatistics& h = halves_step.round[static_cast<std::size_t>(k)];
    const bsg::algos::AgentRoundStatistics& w = whole_step.round[static_cast<std::size_t>(k)];
    EXPECT_EQ(h.position, w.position);
    EXPECT_NEAR(mpi.average(h.kl), w.kl, 1e-12 * w.kl) << "agent " << k;  // a mean over rows: halves average
    EXPECT_NEAR(h.step_norm, w.step_norm, 1e-12 * w.step_norm) << "agent " << k;
    if (config.alg == bsg::Algorithm::happo) {  // Adam's moments of the agent's PPO
      const Eigen::VectorXd adam_halves = concatenated(update_state(*on_halves.ppo_updates[static_cast<std::size_t>(k)]));
      const Eigen::VectorXd adam_whole = concatenated(update_state(*on_whole.ppo_updates[static_cast<std::size_t>(k)]));
      EXPECT_LE((adam_halves - adam_whole).norm(), 1e-12 * adam_whole.norm()) << "agent " << k;
    }
  }
  EXPECT_EQ(moved, kAgents);
}

}  // namespace

TEST(MultiAgentFamilyMpi, HappoStepOnHalvesEqualsOneProcessOnTheWholeBatch) {
  expect_halves_take_the_whole_step(
      family_config({"alg=happo", "dtype=float64", "policy_minibatch_size=64", "seed=3"}));
}

TEST(MultiAgentFamilyMpi, MacpoStepOnHalvesEqualsOneProcessOnTheWholeBatch) {
  expect_halves_take_the_whole_step(family_config({"alg=macpo", "dtype=float64", "cost_limit=25", "seed=3"}));
}
