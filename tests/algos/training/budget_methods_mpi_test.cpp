// The budget methods under `mpirun -np 2` (docs/algorithms.md#budget-methods): two ranks that
// each collect half of an epoch log the episode statistics of one process collecting all of it,
// the learner's columns and Simmer's budget included, and Simmer's controllers on both ranks hold
// the state of the one process's. The episodes differ by rank (rank 0's cost nothing, rank 1's cost
// 1 every 5 steps), so a controller fed its own rank's mean episode cost would drift apart from the
// pooled one that the one process sees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "../scripted_env.h"
#include "../scripted_training.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/progress_csv_reader.h"
#include "envs/decorated_env.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;

// ScriptedEnv (100 steps, reward 1 + 0.01 t) whose episode i since the last seeded reset costs 1
// at every periods[min(i, size - 1)]-th step.
class PeriodicCostEnv final : public envs::DecoratedEnv {
 public:
  explicit PeriodicCostEnv(std::vector<int> periods)
      : DecoratedEnv(std::make_unique<testing::ScriptedEnv>(100, std::nullopt, 1000)), periods_(std::move(periods)) {}

  std::span<const double> reset(std::uint64_t seed) override {
    episode_ = 0;
    step_ = 0;
    return inner().reset(seed);
  }
  std::span<const double> reset() override {
    ++episode_;
    step_ = 0;
    return inner().reset();
  }
  envs::StepResult step(std::span<const double> action) override {
    envs::StepResult result = inner().step(action);
    const int period = periods_[std::min(episode_, periods_.size() - 1)];
    result.cost = ++step_ % period == 0 ? 1.0 : 0.0;
    return result;
  }

 private:
  std::vector<int> periods_;
  std::size_t episode_ = 0;
  int step_ = 0;
};

constexpr int kNoCost = 1000;  // a period longer than the episode

struct RunResult {
  std::vector<std::map<std::string, double>> rows;  // rank 0's progress.csv, by column
  std::vector<NamedScalar> simmer_state;            // Simmer's controllers at the end (simmer_algorithm.h)
};

RunResult train(const RunConfig& config, const MpiContext& mpi, std::vector<int> periods) {
  std::unique_ptr<testing::TemporaryDirectory> dir;
  if (mpi.is_root()) dir = std::make_unique<testing::TemporaryDirectory>("budget_mpi");
  const RunDirectory run((dir ? dir->path() : fs::path("unwritten")) / "run");
  OnPolicyTrainer trainer(config, run, mpi, {}, std::make_unique<PeriodicCostEnv>(std::move(periods)));
  trainer.run();
  RunResult result;
  for (const NamedScalar& entry : trainer.algorithm().state()) {
    if (entry.name.starts_with("simmer_")) result.simmer_state.push_back(entry);
  }
  if (!mpi.is_root()) return result;
  const ProgressLogText log = read_progress_log(testing::read_text_file(run.progress()), "progress.csv", config.steps_per_epoch);
  const std::vector<std::string> names = split_csv_line(log.header);
  for (const std::string& line : log.rows) {
    const std::vector<std::string> values = split_csv_line(line);
    std::map<std::string, double>& row = result.rows.emplace_back();
    for (std::size_t i = 0; i < names.size(); ++i) row[names[i]] = std::stod(values[i]);
  }
  return result;
}

TEST(BudgetMethodsMpi, TwoRanksLogTheEpisodesAndBudgetsOfOneProcess) {
  const MpiContext mpi = MpiContext::world();
  ASSERT_EQ(mpi.size(), 2);
  for (const Algorithm alg : {Algorithm::ppo_saute, Algorithm::ppo_early_terminated, Algorithm::ppo_simmer}) {
    SCOPED_TRACE(to_string(alg));
    RunConfig config = testing::scripted_config();  // 400 steps per epoch, episodes of at most 100 steps
    config.alg = alg;
    config.use_cost_value_function = false;
    config.epochs = 3;
    config.num_mini_batches = 8;  // value-net minibatches of 25 on each rank's 200 samples
    // Early termination cuts a period-5 episode at step 50 (cost 10 > 9.5): 200 steps hold whole
    // episodes either way. Saute and Simmer spend the budget in the period-5 episodes (cost 20).
    config.cost_limit = alg == Algorithm::ppo_early_terminated ? 9.5 : 14.0;
    config.budget.simmer_kp = 0.1;
    config.budget.simmer_ki = 0.05;
    config.budget.simmer_polyak = 0.5;
    config.budget.simmer_initial_budget_fraction = 0.5;
    // One process: two episodes without cost, then of period 5; two ranks: rank 0's without, rank 1's of 5.
    const RunResult single = train(config, MpiContext::single_process(), {kNoCost, kNoCost, 5});
    const RunResult ranks = train(config, mpi, {mpi.rank() == 0 ? kNoCost : 5});
    EXPECT_EQ(ranks.simmer_state, single.simmer_state);  // budget, errors and steps, bit for bit
    EXPECT_EQ(single.simmer_state.empty(), alg != Algorithm::ppo_simmer);
    if (!mpi.is_root()) continue;
    ASSERT_EQ(ranks.rows.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      SCOPED_TRACE(k);
      for (const char* column : {"episodes", "episode_return_mean", "episode_cost_mean", "episode_length_mean",
                                 "learner_return_mean", "budget_spent_fraction", "simmer_budget"}) {
        if (ranks.rows[k].count(column) == 0) continue;  // simmer_budget: Simmer's alone
        const double expected = single.rows[k].at(column);
        EXPECT_NEAR(ranks.rows[k].at(column), expected, 1e-12 * (1.0 + std::abs(expected))) << column;
      }
    }
    if (alg == Algorithm::ppo_simmer) {
      EXPECT_NE(single.rows[2].at("simmer_budget"), single.rows[0].at("simmer_budget"));  // it moved
    } else {
      EXPECT_GT(single.rows[0].at("budget_spent_fraction"), 0.0);
      EXPECT_LT(single.rows[0].at("budget_spent_fraction"), 1.0) << "the two kinds of episode differ";
    }
  }
}

}  // namespace
}  // namespace bsg::algos
