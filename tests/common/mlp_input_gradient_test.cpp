// Mlp::input_gradient_batch (dL/dx, a critic's dQ/da) against central differences in the input,
// in both dtypes, over more rows than one chunk; and the pass leaves every existing number alone.
#include <gtest/gtest.h>

#include "common/mlp.h"
#include "finite_differences.h"
#include "random_matrices.h"

namespace bsg {
namespace {

using testing::relative_error;

using testing::uniform_matrix;

// The loss is L = sum_i w_i . y_i, so dL/dx_i = J_i^T w_i.
void check_input_gradient(Dtype dtype, double tolerance) {
  Rng rng(7);
  Mlp net({5, 9, 7, 3}, rng, {.dtype = Dtype::float64});
  const Eigen::Index rows = kBatchChunkRows + 13;  // two chunks
  const Eigen::MatrixXd inputs = uniform_matrix(rows, 5, 1.5, rng);
  const Eigen::MatrixXd weights = uniform_matrix(rows, 3, 1.5, rng);
  // The oracle: central differences of the float64 single-sample forward.
  Eigen::MatrixXd expected(rows, 5);
  const double h = 1e-6;
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < 5; ++j) {
      Eigen::VectorXd plus = inputs.row(i).transpose(), minus = plus;
      plus(j) += h;
      minus(j) -= h;
      expected(i, j) = (net.forward(plus).dot(weights.row(i).transpose()) -
                        net.forward(minus).dot(weights.row(i).transpose())) / (2 * h);
    }
  }
  net.set_dtype(dtype);
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  Eigen::MatrixXd gradient(rows, 5);
  net.input_gradient_batch(weights, workspace, gradient);
  EXPECT_LT(relative_error(gradient, expected), tolerance);
}

TEST(MlpInputGradient, MatchesCentralDifferencesInFloat64) { check_input_gradient(Dtype::float64, 1e-7); }

TEST(MlpInputGradient, MatchesCentralDifferencesInFloat32) { check_input_gradient(Dtype::float32, 1e-5); }

TEST(MlpInputGradient, LeavesTheParameterGradientOfTheSameForwardPassUnchanged) {
  Rng rng(3);
  Mlp net({4, 6, 2}, rng, {.dtype = Dtype::float64});
  const Eigen::MatrixXd inputs = uniform_matrix(10, 4, 1.5, rng);
  const Eigen::MatrixXd weights = uniform_matrix(10, 2, 1.5, rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  Eigen::VectorXd before(net.num_parameters()), after(net.num_parameters());
  net.backward_batch(weights, workspace, before);
  Eigen::MatrixXd gradient(10, 4);
  net.input_gradient_batch(weights, workspace, gradient);
  net.backward_batch(weights, workspace, after);
  EXPECT_EQ(before, after);
}

TEST(MlpInputGradient, RejectsMisshapenMatrices) {
  Rng rng(3);
  Mlp net({4, 6, 2}, rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(Eigen::MatrixXd::Zero(3, 4), workspace);
  Eigen::MatrixXd gradient(3, 4);
  EXPECT_THROW(net.input_gradient_batch(Eigen::MatrixXd::Zero(3, 3), workspace, gradient), std::invalid_argument);
  Eigen::MatrixXd wrong(2, 4);
  EXPECT_THROW(net.input_gradient_batch(Eigen::MatrixXd::Zero(3, 2), workspace, wrong), std::invalid_argument);
}

}  // namespace
}  // namespace bsg
