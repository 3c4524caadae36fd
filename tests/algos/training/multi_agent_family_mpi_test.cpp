// The multi-agent family under `mpirun -np 2`: each rank collects its half of the team steps, the
// gradients are averaged, and every rank ends with identical actors, critics, Adam states and
// multipliers; rank 0 gathers both ranks' evaluation episodes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

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

Eigen::VectorXd everything(const bsg::algos::MultiAgentFamily& family) {
  std::vector<double> values;
  const auto append = [&](const Eigen::VectorXd& v) { values.insert(values.end(), v.data(), v.data() + v.size()); };
  const bsg::algos::MultiAgentNetworks& networks = family.networks();
  for (int s = 0; s < networks.slot_count(); ++s) {
    const bsg::algos::AgentSlot& slot = networks.slot(s);
    append(slot.policy.mean_net().parameters());
    append(slot.policy.log_stds());
    append(slot.value.net().parameters());
    append(slot.cost_value->net().parameters());
    append(slot.value.optimizer().second_moment());
    for (const bsg::algos::NamedScalar& entry : family.slot_algorithm(s).state()) values.push_back(entry.value);
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

TEST(MultiAgentFamilyMpi, RanksEndWithIdenticalNetworksAndMultipliers) {
  const bsg::MpiContext mpi = bsg::MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle2-v0", "alg=mappo-lag", "epochs=2", "steps_per_epoch=400",
                           "max_ep_len=100", "hidden_sizes=[8]", "eval_episodes=4", "check_freq=1",
                           "policy_minibatch_size=200", "lambda_lr=0.01", "cost_limit=0"};
  const bsg::RunConfig config = bsg::algos::resolve_training_config(request);
  std::string directory;
  if (mpi.is_root()) {
    char pattern[] = "/tmp/bsg_multi_agent_mpi_test_XXXXXX";
    directory = mkdtemp(pattern);
  }
  bsg::algos::MultiAgentTrainer trainer(config, bsg::algos::RunDirectory(fs::path(directory) / "run"), mpi, {});
  const bsg::algos::TrainingOutcome outcome = trainer.run();
  EXPECT_TRUE(outcome.finished);
  EXPECT_TRUE(same_on_all_ranks(everything(trainer.multi_agent()), mpi));
  if (mpi.is_root()) {
    ASSERT_TRUE(outcome.evaluation.has_value());
    EXPECT_EQ(outcome.evaluation->episodes.size(), 4u);  // 2 per rank, gathered
    std::error_code ignored;
    fs::remove_all(directory, ignored);
  }
}
