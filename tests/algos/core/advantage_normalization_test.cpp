// Standardising (Q6) and centring (also Q6) the advantages against hand-computed
// batches: centring removes each column's mean and keeps its scale.
#include "algos/core/advantage_normalization.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bsg::algos {
namespace {

TEST(AdvantageNormalization, CenteringSubtractsEachMeanAndKeepsTheScale) {
  Eigen::VectorXd reward(4);
  reward << 1.0, 2.0, 3.0, 6.0;  // mean 3
  Eigen::MatrixXd costs(4, 2);
  costs << 0.0, 4.0,  //
      1.0, 4.0,       //
      1.0, 8.0,       //
      2.0, 0.0;       // means 1 and 4
  center_advantages(reward, costs, MpiContext::single_process());
  EXPECT_DOUBLE_EQ(reward[0], -2.0);
  EXPECT_DOUBLE_EQ(reward[1], -1.0);
  EXPECT_DOUBLE_EQ(reward[2], 0.0);
  EXPECT_DOUBLE_EQ(reward[3], 3.0);
  const double expected_costs[4][2] = {{-1.0, 0.0}, {0.0, 0.0}, {0.0, 4.0}, {1.0, -4.0}};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 2; ++c) EXPECT_DOUBLE_EQ(costs(r, c), expected_costs[r][c]) << r << "," << c;
  }
}

TEST(AdvantageNormalization, StandardizingDividesTheRewardsByTheirStdAndOnlyCentresTheCosts) {
  Eigen::VectorXd reward(4);
  reward << 1.0, 2.0, 3.0, 6.0;  // mean 3, population variance (4 + 1 + 0 + 9) / 4 = 3.5
  Eigen::MatrixXd costs(4, 1);
  costs << 0.0, 1.0, 1.0, 2.0;
  standardize_advantages(reward, costs, MpiContext::single_process());
  const double std = std::sqrt(3.5) + 1e-8;
  EXPECT_NEAR(reward[0], -2.0 / std, 1e-12);
  EXPECT_NEAR(reward[3], 3.0 / std, 1e-12);
  EXPECT_DOUBLE_EQ(costs(0, 0), -1.0);
  EXPECT_DOUBLE_EQ(costs(3, 0), 1.0);
}

}  // namespace
}  // namespace bsg::algos
