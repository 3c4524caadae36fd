// The Fisher-vector product (docs/algorithms.md#fisher-vector-product) against the finite-difference Hessian
// of the mean KL of docs/algorithms.md#mean-kl, and its invariants from docs/algorithms.md#test-oracles.
#include "algos/trust_region/fisher_vector_product.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "../../common/finite_differences.h"
#include "../../common/random_matrices.h"

namespace bsg::algos {
namespace {

using testing::finite_difference_gradient;
using testing::relative_error;

using testing::normal_matrix;

Eigen::MatrixXd every_fourth_row(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd rows((m.rows() + 3) / 4, m.cols());
  for (Eigen::Index i = 0; i < rows.rows(); ++i) rows.row(i) = m.row(4 * i);
  return rows;
}

struct Fixture {
  Rng rng{11};
  GaussianPolicy policy{3, 2, {5, 4}, rng};
  Eigen::MatrixXd observations = normal_matrix(10, 3, rng);
  Eigen::VectorXd direction = normal_matrix(policy.mean_net().num_parameters(), 1, rng);
};

TEST(FisherVectorProduct, EqualsFiniteDifferenceHessianOfMeanKlPlusDamping) {
  Fixture f;
  f.policy.set_std(0.3);
  FisherVectorProduct fvp(f.policy, f.observations, MpiContext::single_process());
  Eigen::VectorXd product(f.direction.size());
  fvp.apply(f.direction, product);

  // Oracle: KL(theta_old || theta) on rows 0, 4, 8; its Hessian times v by central
  // differences of its finite-difference gradient.
  const Eigen::MatrixXd sub = every_fourth_row(f.observations);
  const Eigen::VectorXd theta_old = f.policy.mean_net().parameters();
  GaussianPolicy probe = f.policy;
  MlpBatchWorkspace workspace;
  const Eigen::MatrixXd old_means = probe.mean_net().forward_batch(sub, workspace);
  const auto kl = [&](const Eigen::VectorXd& theta) {
    probe.mean_net().set_parameters(theta);
    return probe.mean_kl(old_means, probe.mean_net().forward_batch(sub, workspace));
  };
  const double h = 1e-4;
  const Eigen::VectorXd hessian_v = (finite_difference_gradient(kl, theta_old + h * f.direction, h) -
                                     finite_difference_gradient(kl, theta_old - h * f.direction, h)) /
                                    (2.0 * h);
  EXPECT_LT(relative_error(product, hessian_v + 0.1 * f.direction), 1e-6);
  EXPECT_EQ(fvp.num_samples(), 3);
  EXPECT_EQ(fvp.call_count(), 1);
}

TEST(FisherVectorProduct, UsesRowsZeroFourEightOnly) {
  Fixture f;
  FisherVectorProduct strided(f.policy, f.observations, MpiContext::single_process());
  FisherVectorProduct on_subset(f.policy, every_fourth_row(f.observations), MpiContext::single_process(),
                                FisherVectorProductOptions{.subsample_stride = 1});
  Eigen::VectorXd a(f.direction.size()), b(f.direction.size());
  strided.apply(f.direction, a);
  on_subset.apply(f.direction, b);
  EXPECT_LT(relative_error(a, b), 1e-14);
  // Changing a row that is not sub-sampled changes nothing.
  Eigen::MatrixXd changed = f.observations;
  changed.row(5).setConstant(9.0);
  FisherVectorProduct changed_fvp(f.policy, changed, MpiContext::single_process());
  changed_fvp.apply(f.direction, b);
  EXPECT_EQ(a, b);
}

TEST(FisherVectorProduct, IsSymmetricAndDampedPositiveDefinite) {
  Fixture f;
  FisherVectorProduct fvp(f.policy, f.observations, MpiContext::single_process());
  Rng rng(3);
  const Eigen::VectorXd u = normal_matrix(f.direction.size(), 1, rng);
  Eigen::VectorXd fu(u.size()), fv(u.size());
  fvp.apply(u, fu);
  fvp.apply(f.direction, fv);
  EXPECT_NEAR(f.direction.dot(fu), u.dot(fv), 1e-12 * std::abs(u.dot(fv)));
  EXPECT_GE(f.direction.dot(fv), 0.1 * f.direction.squaredNorm());
}

TEST(FisherVectorProduct, UndampedPartScalesAsOneOverSigmaSquared) {
  Fixture f;
  f.policy.set_std(0.5);
  FisherVectorProduct wide(f.policy, f.observations, MpiContext::single_process(),
                           FisherVectorProductOptions{.damping_coeff = 0.0});
  f.policy.set_std(0.25);
  FisherVectorProduct narrow(f.policy, f.observations, MpiContext::single_process(),
                             FisherVectorProductOptions{.damping_coeff = 0.0});
  Eigen::VectorXd a(f.direction.size()), b(f.direction.size());
  wide.apply(f.direction, a);
  narrow.apply(f.direction, b);
  EXPECT_LT(relative_error(b, 4.0 * a), 1e-13);
}

TEST(FisherVectorProduct, IsLinearisedAtConstructionTime) {
  Fixture f;
  FisherVectorProduct fvp(f.policy, f.observations, MpiContext::single_process());
  Eigen::VectorXd before(f.direction.size()), after(f.direction.size());
  fvp.apply(f.direction, before);
  f.policy.mean_net().set_parameters(f.policy.mean_net().parameters() * 2.0);  // e.g. a line-search trial
  f.policy.set_std(0.1);
  fvp.apply(f.direction, after);
  EXPECT_EQ(before, after);
}

TEST(FisherVectorProduct, BadInputGivesExceptions) {
  Fixture f;
  EXPECT_THROW(FisherVectorProduct(f.policy, Eigen::MatrixXd::Zero(4, 2), MpiContext::single_process()),
               std::invalid_argument);
  EXPECT_THROW(FisherVectorProduct(f.policy, Eigen::MatrixXd::Zero(0, 3), MpiContext::single_process()),
               std::invalid_argument);
  EXPECT_THROW(FisherVectorProduct(f.policy, f.observations, MpiContext::single_process(),
                                   FisherVectorProductOptions{.subsample_stride = 0}),
               std::invalid_argument);
  FisherVectorProduct fvp(f.policy, f.observations, MpiContext::single_process());
  Eigen::VectorXd product(f.direction.size());
  try {
    fvp.apply(Eigen::VectorXd::Zero(3), product);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("direction has 3 entries"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fvp.apply(product, product), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
