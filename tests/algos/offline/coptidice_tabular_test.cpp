// COptiDICE (algos/offline/coptidice.h) learns the solution of a small constrained MDP that this test
// solves on its own. The CMDP: 3 states, 2 actions, deterministic transitions, one-hot observations,
// every episode starting in state 0, gamma 0.8. Its dataset is four 3-step episodes ended by time
// limits; their 12 rows give the data distribution d_D(s, a) = count / 12, and their first rows (share
// 4 / 12, COptiDICE's p0 share) the initial distribution p0 = (1, 0, 0).
//
// The oracle. With chi2, f(x) = (x - 1)^2 / 2, and cost_ub_epsilon = 0, the implemented objective is
// the textbook COptiDICE primal
//   max_d  sum d r - alpha sum d_D f(d / d_D)
//   s.t.   sum_a d(s, a) - gamma sum_{s', a'} 1[T(s', a') = s] d(s', a') = (1 - gamma) p0(s)   (nu(s))
//          sum d c <= l                                                                      (lambda)
// whose Lagrangian, maximised over w = d / d_D in closed form, is L_nu + lambda l: nu's step descends
// L_nu and lambda's descends lambda (l - E_D[w c]), both gradients of that dual. The mapping to bsg's
// options: r = reward_scale (0.5) x the rows' reward, c = cost_scale (1) x their cost, so lambda is
// bsg's softplus(parameter) itself; l is bsg's threshold cost_limit (1 - gamma^T) / ((1 - gamma) T)
// (OSRL's, not the paper's normalised limit, docs/datasets.md), which the oracle takes as it is. The
// flow constraint holds at every row because a time limit bootstraps in bsg (coptidice.h; OSRL's
// (1 - done) would cut each episode's last row from it, another program). Training on the full dataset
// as one batch makes every mean an exact expectation under d_D, and the initial rows' mean of nu over
// their share the mean under p0. alpha = 1 leaves the optimum d* strictly positive (checked), so d >= 0
// is slack and the optimum solves an equality-constrained QP whose KKT system
//   alpha d / d_D + nu(s) - gamma nu(T(s, a)) + lambda c = r + alpha,   the flows,   (sum d c = l)
// is solved here by a dense LU. Its first row is alpha (w - 1) = r - lambda c + gamma nu(s') - nu(s) =
// e, bsg's w = max(0, e / alpha + 1) with every w > 0: nu, lambda and w compare one to one.
//
// Tabular nu: the networks have no hidden layer (hidden_sizes {}), nu(s) = W x(s) + b, linear in the
// standardised one-hot x(s), which can take any value per state; their minimum is then any table too.
#include "algos/offline/coptidice.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "algos/offline/offline_batches.h"

namespace bsg::algos {
namespace {
namespace coptidice_tabular_test {

constexpr int kStates = 3;
constexpr int kActions = 2;
constexpr int kPairs = kStates * kActions;
constexpr double kGamma = 0.8;
constexpr double kAlpha = 1.0;
constexpr double kRewardScale = 0.5;
constexpr int kEpisodeLength = 3;              // T of the threshold; every episode here has 3 rows
constexpr double kOsrlLambdaParameter = 1.0;  // lambda's parameter at the start (OSRL's torch.ones)

// T(s, a), r(s, a) and c(s, a) before scaling (values exact in float, the dataset's type).
constexpr int kNext[kStates][kActions] = {{1, 2}, {0, 2}, {0, 1}};
constexpr double kReward[kStates][kActions] = {{0.0, 1.0}, {0.25, 1.0}, {0.0, 0.5}};
constexpr double kCost[kStates][kActions] = {{0.0, 1.0}, {0.0, 1.0}, {0.0, 0.5}};
constexpr double kActionValue[kActions] = {-0.5, 0.5};  // the dataset's 1-D action of each discrete action

// Each episode's actions from state 0.
const std::vector<std::vector<int>> kEpisodes{{0, 0, 1}, {1, 0, 0}, {0, 1, 1}, {1, 1, 0}};

double threshold_of(double cost_limit) {
  // l = d (1 - gamma^T) / ((1 - gamma) T) = d (1 - 0.512) / 0.6
  return cost_limit * (1.0 - kGamma * kGamma * kGamma) / ((1.0 - kGamma) * kEpisodeLength);
}

int pair_index(int s, int a) { return s * kActions + a; }

struct Row {
  int state;
  int action;
  bool first;
};

std::vector<Row> episode_rows() {
  std::vector<Row> rows;
  for (const std::vector<int>& actions : kEpisodes) {
    int s = 0;
    for (std::size_t t = 0; t < actions.size(); ++t) {
      rows.push_back({s, actions[t], t == 0});
      s = kNext[s][actions[t]];
    }
  }
  return rows;
}

// d_D and p0 counted from the rows.
struct DataDistribution {
  Eigen::VectorXd d_data = Eigen::VectorXd::Zero(kPairs);
  Eigen::VectorXd p0 = Eigen::VectorXd::Zero(kStates);
};

DataDistribution data_distribution(const std::vector<Row>& rows) {
  DataDistribution dist;
  double firsts = 0.0;
  for (const Row& row : rows) {
    dist.d_data(pair_index(row.state, row.action)) += 1.0 / static_cast<double>(rows.size());
    if (row.first) {
      dist.p0(row.state) += 1.0;
      firsts += 1.0;
    }
  }
  dist.p0 /= firsts;
  return dist;
}

struct KktSolution {
  Eigen::VectorXd d;    // d*(s, a)
  Eigen::VectorXd w;    // d* / d_D
  Eigen::VectorXd nu;   // nu*(s)
  double lambda = 0.0;  // the cost constraint's multiplier
  double cost = 0.0;    // sum d* c
};

// The KKT system of the QP above. With a `threshold`, the cost constraint is an equality and lambda
// an unknown; without, lambda is `fixed_lambda` (0: the constraint left out, the unconstrained optimum).
KktSolution solve_kkt(const DataDistribution& dist, std::optional<double> threshold, double fixed_lambda = 0.0) {
  const int size = kPairs + kStates + (threshold ? 1 : 0);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(size, size);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
  for (int s = 0; s < kStates; ++s) {
    for (int a = 0; a < kActions; ++a) {
      const int i = pair_index(s, a);
      const double c = kCost[s][a];  // cost_scale 1
      k(i, i) = kAlpha / dist.d_data(i);
      rhs(i) = kRewardScale * kReward[s][a] + kAlpha;
      k(i, kPairs + s) += 1.0;  // nu(s) - gamma nu(T(s, a))
      k(i, kPairs + kNext[s][a]) -= kGamma;
      k(kPairs + s, i) += 1.0;  // the flow of s: sum_a d(s, a) - gamma times what leads to s
      k(kPairs + kNext[s][a], i) -= kGamma;
      if (threshold) {
        k(i, kPairs + kStates) = c;
        k(kPairs + kStates, i) = c;
      } else {
        rhs(i) -= fixed_lambda * c;
      }
    }
  }
  for (int s = 0; s < kStates; ++s) rhs(kPairs + s) = (1.0 - kGamma) * dist.p0(s);
  if (threshold) rhs(kPairs + kStates) = *threshold;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(k);
  EXPECT_TRUE(lu.isInvertible());
  const Eigen::VectorXd x = lu.solve(rhs);
  KktSolution solution;
  solution.d = x.head(kPairs);
  solution.w = solution.d.cwiseQuotient(dist.d_data);
  solution.nu = x.segment(kPairs, kStates);
  solution.lambda = threshold ? x(kPairs + kStates) : fixed_lambda;
  for (int s = 0; s < kStates; ++s) {
    for (int a = 0; a < kActions; ++a) solution.cost += solution.d(pair_index(s, a)) * kCost[s][a];
  }
  return solution;
}

OfflineDataset tabular_dataset(const std::vector<Row>& rows) {
  OfflineDataset dataset;
  dataset.observation_dim = kStates;
  dataset.action_dim = 1;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& row = rows[i];
    const int next = kNext[row.state][row.action];
    for (int s = 0; s < kStates; ++s) dataset.observations.push_back(s == row.state ? 1.0f : 0.0f);
    for (int s = 0; s < kStates; ++s) dataset.next_observations.push_back(s == next ? 1.0f : 0.0f);
    dataset.actions.push_back(static_cast<float>(kActionValue[row.action]));
    dataset.rewards.push_back(static_cast<float>(kReward[row.state][row.action]));
    dataset.costs.push_back(static_cast<float>(kCost[row.state][row.action]));
    dataset.terminals.push_back(0.0f);
    const bool last = i + 1 == rows.size() || rows[i + 1].first;
    dataset.timeouts.push_back(last ? 1.0f : 0.0f);
  }
  return dataset;
}

// Every row once, in order, each filled as OfflineBatches::sample fills one (observations standardised
// with the training rows' constants, `initial` 1 on the episodes' first rows).
OfflineBatch full_batch(const OfflineDataset& dataset, const ObservationScaling& scaling) {
  const std::vector<char> first = episode_first_rows(dataset);
  const Eigen::Index n = static_cast<Eigen::Index>(dataset.size());
  OfflineBatch batch;
  batch.observations.resize(n, kStates);
  batch.next_observations.resize(n, kStates);
  batch.actions.resize(n, 1);
  batch.rewards.resize(n);
  batch.costs.resize(n);
  batch.terminals.resize(n);
  batch.initial.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int s = 0; s < kStates; ++s) {
      const std::size_t k = static_cast<std::size_t>(i * kStates + s);
      batch.observations(i, s) = (dataset.observations[k] - scaling.mean(s)) / scaling.std(s);
      batch.next_observations(i, s) = (dataset.next_observations[k] - scaling.mean(s)) / scaling.std(s);
    }
    const std::size_t row = static_cast<std::size_t>(i);
    batch.actions(i, 0) = dataset.actions[row];
    batch.rewards(i) = dataset.rewards[row];
    batch.costs(i) = dataset.costs[row];
    batch.terminals(i) = dataset.terminals[row];
    batch.initial(i) = first[row];
  }
  return batch;
}

struct Trained {
  Eigen::VectorXd w;   // per (s, a), from bsg's nu and lambda
  Eigen::VectorXd nu;  // per state
  double lambda = 0.0;
};

// bsg's COptiDICE on the full batch of the dataset's rows.
class TabularRun {
 public:
  TabularRun(double cost_limit, double lambda_parameter)
      : rows_(episode_rows()),
        dataset_(tabular_dataset(rows_)),
        batches_(dataset_, all_rows(dataset_), static_cast<int>(dataset_.size())),
        batch_(full_batch(dataset_, batches_.scaling())),
        learner_(kStates, 1, batches_.scaling(), options(cost_limit, batches_.statistics()), init_) {
    learner_.set_lambda_parameter(lambda_parameter);
  }

  void update(int count) {
    for (int u = 0; u < count; ++u) learner_.update(batch_, noise_);
  }

  Trained result() {
    Trained trained;
    trained.lambda = softplus(learner_.lambda_parameter());
    learner_.compute_ratios(batch_, trained.lambda);
    trained.w.setConstant(kPairs, -1.0);
    trained.nu.setZero(kStates);
    for (Eigen::Index i = 0; i < batch_.observations.rows(); ++i) {
      const Row& row = rows_[static_cast<std::size_t>(i)];
      const int p = pair_index(row.state, row.action);
      if (trained.w(p) >= 0.0) {
        EXPECT_DOUBLE_EQ(learner_.ratios()(i), trained.w(p)) << "rows of one pair differ";
      }
      trained.w(p) = learner_.ratios()(i);
      const Eigen::VectorXd x = batch_.observations.row(i).transpose();
      trained.nu(row.state) = std::min(learner_.nu(0).forward(x)[0], learner_.nu(1).forward(x)[0]);
    }
    return trained;
  }

  const TrainingStatistics& statistics() const { return batches_.statistics(); }
  const OfflineBatch& batch() const { return batch_; }

 private:
  static COptiDiceOptions options(double cost_limit, const TrainingStatistics& statistics) {
    COptiDiceOptions options;
    options.hidden_sizes = {};
    options.gamma = kGamma;
    options.critic_lr = 0.01;  // nu and lambda: fast enough for a few thousand full-batch updates
    options.scalar_lr = 0.01;
    options.actor_lr = 1e-3;
    options.alpha = kAlpha;
    options.cost_ub_epsilon = 0.0;
    options.f_divergence = FDivergence::chi2;
    options.reward_scale = kRewardScale;
    options.cost_scale = 1.0;
    options.cost_limit = cost_limit;
    options.episode_length = kEpisodeLength;
    options.initial_state_proportion = statistics.initial_state_proportion;
    options.action_std = statistics.action_std;
    return options;
  }

  std::vector<Row> rows_;
  OfflineDataset dataset_;
  OfflineBatches batches_;
  OfflineBatch batch_;
  Rng init_{5};
  Rng noise_{6};
  COptiDice learner_;
};

TEST(COptiDiceTabular, DatasetCarriesTheChosenDistributions) {
  // The episodes' 12 rows by hand: (0,0) x3, (0,1) x3, (1,0) x2, (1,1) x1, (2,0) x1, (2,1) x2; each of the
  // 4 episodes starts in state 0 (its first rows 0, 3, 6, 9).
  const std::vector<Row> rows = episode_rows();
  const DataDistribution dist = data_distribution(rows);
  Eigen::VectorXd counts(kPairs);
  counts << 3, 3, 2, 1, 1, 2;
  EXPECT_LT((dist.d_data - counts / 12.0).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(dist.p0, Eigen::Vector3d(1.0, 0.0, 0.0));
  TabularRun run(0.4, kOsrlLambdaParameter);
  EXPECT_DOUBLE_EQ(run.statistics().initial_state_proportion, 4.0 / 12.0);
  Eigen::VectorXd initial = Eigen::VectorXd::Zero(12);
  initial << 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0;
  EXPECT_EQ(run.batch().initial, initial);
}

// The limit d = 0.4, l = 0.4 (1 - 0.8^3) / (0.2 x 3) = 0.325: below the unconstrained optimum's cost, so
// the constraint binds. bsg's w, nu and lambda are compared with the KKT solution from OSRL's start
// lambda = softplus(1) (it falls to lambda*) and from lambda = softplus(-10) = 4.5e-5 (it rises).
// Tolerance 1e-8: the model is exact (tabular nu, the full data as the batch), so what is left is
// optimisation error. In this region (every w > 0) the chi2 dual is exactly quadratic in (nu, lambda)
// and Adam (lr 0.01, full batch) reaches it to rounding, 2e-15 in w, 8e-15 in nu and lambda, by 1500
// updates from either start (measured); later, as Adam's second moment forgets the early gradients,
// its step lr / sqrt(v) outgrows the curvature and it oscillates again (from about 4500 updates, up to
// 5e-3 at 10000), so the test stops at 3000. 1e-8 is 1e7 times below the constraint's effect on w.
TEST(COptiDiceTabular, BindingCostConstraintMatchesTheKktSolution) {
  const DataDistribution dist = data_distribution(episode_rows());
  const double limit = 0.4;
  const double l = threshold_of(limit);
  const KktSolution kkt = solve_kkt(dist, l);
  const KktSolution unconstrained = solve_kkt(dist, std::nullopt);
  // The oracle's own conditions: d* a distribution, strictly positive (so d >= 0 is slack and w =
  // max(0, e / alpha + 1) is e / alpha + 1), the cost on the limit, the multiplier positive, and the
  // unconstrained optimum over the limit.
  EXPECT_NEAR(kkt.d.sum(), 1.0, 1e-12);
  EXPECT_GT(kkt.d.minCoeff(), 0.01);
  EXPECT_NEAR(kkt.cost, l, 1e-12);
  EXPECT_GT(kkt.lambda, 0.5);
  EXPECT_GT(unconstrained.cost, l + 0.1);
  EXPECT_GT((kkt.w - unconstrained.w).cwiseAbs().maxCoeff(), 0.1);  // lambda changes w
  for (double start : {kOsrlLambdaParameter, -10.0}) {
    TabularRun run(limit, start);
    run.update(3000);
    const Trained trained = run.result();
    EXPECT_LT((trained.w - kkt.w).cwiseAbs().maxCoeff(), 1e-8) << start;
    EXPECT_LT((trained.nu - kkt.nu).cwiseAbs().maxCoeff(), 1e-8) << start;
    EXPECT_NEAR(trained.lambda, kkt.lambda, 1e-8) << start;
  }
}

// The limit d = 0.8, l = 0.651: above the unconstrained optimum's cost (0.464), so lambda* = 0 and d* is
// the unconstrained QP's. bsg's lambda = softplus(p) reaches 0 only as p -> -infinity, and Adam moves p
// no faster than its second moment forgets (lambda about e^{-t / 2000}: from OSRL's start 1.31 it is
// 0.008 after 3000 updates, measured), so the run starts at p = -10 (lambda 4.5e-5) and must keep
// lambda falling. Then w and nu are compared with the KKT solution at bsg's lambda (1e-8, as above;
// measured 8e-10 in w, 3e-9 in nu) and with the unconstrained one, from which they may differ by
// lambda |d(w, nu) / d lambda| more, the slopes taken from the oracle (d* is affine in a fixed lambda).
TEST(COptiDiceTabular, SlackCostConstraintLeavesLambdaAtZero) {
  const DataDistribution dist = data_distribution(episode_rows());
  const double limit = 0.8;
  const double l = threshold_of(limit);
  const KktSolution unconstrained = solve_kkt(dist, std::nullopt);
  EXPECT_NEAR(unconstrained.d.sum(), 1.0, 1e-12);
  EXPECT_GT(unconstrained.d.minCoeff(), 0.01);
  EXPECT_LT(unconstrained.cost, l - 0.1);
  const KktSolution at_one = solve_kkt(dist, std::nullopt, 1.0);
  const double w_slope = (at_one.w - unconstrained.w).cwiseAbs().maxCoeff();
  const double nu_slope = (at_one.nu - unconstrained.nu).cwiseAbs().maxCoeff();

  const double start = -10.0;
  TabularRun run(limit, start);
  run.update(3000);
  const Trained trained = run.result();
  EXPECT_LT(trained.lambda, 1e-6);
  EXPECT_LT(trained.lambda, softplus(start));
  const KktSolution at_lambda = solve_kkt(dist, std::nullopt, trained.lambda);
  EXPECT_LT((trained.w - at_lambda.w).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((trained.nu - at_lambda.nu).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((trained.w - unconstrained.w).cwiseAbs().maxCoeff(), trained.lambda * w_slope + 1e-8);
  EXPECT_LT((trained.nu - unconstrained.nu).cwiseAbs().maxCoeff(), trained.lambda * nu_slope + 1e-8);

  TabularRun from_osrl_start(limit, kOsrlLambdaParameter);
  from_osrl_start.update(3000);
  EXPECT_LT(from_osrl_start.result().lambda, 0.05);  // from 1.31: the slack constraint lets it fall
}

}  // namespace coptidice_tabular_test
}  // namespace
}  // namespace bsg::algos
