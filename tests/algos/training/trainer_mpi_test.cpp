// Training under `mpirun -np 2` (docs/algorithms.md#across-mpi-ranks): every rank ends with identical
// parameters, normalisers and algorithm state, and rank 0 writes the run
// directory; the episode statistics are pooled over both ranks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "algos/training/progress_csv.h"
#include "algos/training/on_policy_trainer.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace fs = std::filesystem;

namespace {

// Rank 0's values on every rank, compared with the local ones bit for bit.
bool same_on_all_ranks(const Eigen::VectorXd& local, const bsg::MpiContext& mpi) {
  Eigen::VectorXd root = local;
  mpi.broadcast_from_root(root);
  const double differs = (root.array() != local.array()).any() ? 1.0 : 0.0;
  return mpi.max(differs) == 0.0;
}

Eigen::VectorXd everything(const bsg::algos::ActorCritic& ac, const bsg::algos::OnPolicyAlgorithm& algorithm) {
  std::vector<double> values;
  const auto append = [&](const Eigen::VectorXd& v) { values.insert(values.end(), v.data(), v.data() + v.size()); };
  append(ac.policy.mean_net().parameters());
  append(ac.value.net().parameters());
  append(ac.cost_value.net().parameters());
  append(ac.value.optimizer().first_moment());
  append(ac.cost_value.optimizer().second_moment());
  append(ac.observation_normalizer.mean());
  append(ac.observation_normalizer.std());
  append(ac.return_normalizer.std());
  for (const bsg::algos::NamedScalar& s : algorithm.state()) values.push_back(s.value);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

TEST(TrainerMpi, RanksEndWithIdenticalParametersAndRankZeroWritesTheRun) {
  const bsg::MpiContext mpi = bsg::MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=lag-trpo", "epochs=3", "steps_per_epoch=1000",
                           "eval_episodes=4", "cost_limit=1", "check_freq=1"};
  const bsg::RunConfig config = bsg::resolve_run_config(request).config;

  std::string directory;
  if (mpi.is_root()) {
    char pattern[] = "/tmp/bsg_trainer_mpi_test_XXXXXX";
    directory = mkdtemp(pattern);
  }
  bsg::algos::OnPolicyTrainer trainer(config, bsg::algos::RunDirectory(fs::path(directory) / "run"), mpi, {});
  const bsg::algos::TrainingOutcome outcome = trainer.run();
  EXPECT_TRUE(outcome.finished);
  EXPECT_TRUE(same_on_all_ranks(everything(trainer.actor_critic(), trainer.algorithm()), mpi));

  if (mpi.is_root()) {
    ASSERT_TRUE(outcome.evaluation.has_value());
    EXPECT_EQ(outcome.evaluation->episodes.size(), 4u);  // 2 per rank, gathered
    std::ifstream csv(fs::path(directory) / "run" / "progress.csv");
    std::string header;
    std::string row;
    std::getline(csv, header);
    std::getline(csv, row);
    const auto names = bsg::algos::split_csv_line(header);
    const auto values = bsg::algos::split_csv_line(row);
    const auto column = static_cast<std::size_t>(std::find(names.begin(), names.end(), "episodes") - names.begin());
    ASSERT_LT(column, values.size());
    EXPECT_EQ(values[column], "4");  // 500 steps per rank, 2 episodes of 250 on each of 2 ranks
    fs::remove_all(directory);
  } else {
    EXPECT_FALSE(outcome.evaluation.has_value());
  }
}
