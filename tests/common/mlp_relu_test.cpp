// The MLP with relu hidden layers (MlpOptions::activation, docs/algorithms.md#networks): the forward
// pass against a loop written from max(0, W x + b), and every derivative pass (parameter gradient,
// input gradient, Jacobian-vector product, Gauss-Newton product) against central differences, in
// float64 and float32, over more rows than one chunk.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/mlp.h"
#include "finite_differences.h"
#include "random_matrices.h"
#include "reference_mlp.h"

namespace bsg {
namespace {

using testing::finite_difference_directional;
using testing::finite_difference_gradient;
using testing::reference_forward;
using testing::relative_error;

constexpr MlpOptions kRelu64{.dtype = Dtype::float64, .activation = Activation::relu};

using testing::uniform_matrix;

// Rows of inputs with every hidden pre-activation at least `margin` away from the kink, so that
// central differences of step h < margin see a smooth function.
Eigen::MatrixXd inputs_away_from_kinks(const Mlp& net, Eigen::Index rows, double margin, Rng& rng) {
  Eigen::MatrixXd inputs(rows, net.input_size());
  Eigen::Index kept = 0;
  while (kept < rows) {
    const Eigen::VectorXd x = uniform_matrix(net.input_size(), 1, 2.0, rng);
    Eigen::VectorXd a = x;
    bool clear = true;
    for (int layer = 0; layer + 1 < net.num_layers() && clear; ++layer) {
      const Eigen::VectorXd z = net.weights(layer) * a + net.bias(layer);
      clear = z.cwiseAbs().minCoeff() > margin;
      a = z.cwiseMax(0.0);
    }
    if (clear) inputs.row(kept++) = x.transpose();
  }
  return inputs;
}

TEST(MlpRelu, ForwardMatchesTheLoopForSampleAndBatchInBothDtypes) {
  Rng rng(21);
  const std::vector<int> sizes{5, 7, 6, 3};
  Mlp net(sizes, rng, kRelu64);
  EXPECT_EQ(net.activation(), Activation::relu);
  const Eigen::MatrixXd inputs = uniform_matrix(kBatchChunkRows + 9, 5, 2.0, rng);
  for (const Dtype dtype : {Dtype::float64, Dtype::float32}) {
    net.set_dtype(dtype);
    const double tolerance = dtype == Dtype::float64 ? 1e-13 : 2e-6;
    MlpBatchWorkspace workspace;
    const Eigen::MatrixXd outputs = net.forward_batch(inputs, workspace);
    MlpSampleWorkspace sample_workspace;
    Eigen::VectorXd output(3);
    for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
      const Eigen::VectorXd expected = reference_forward(sizes, net.parameters(), inputs.row(i).transpose(), Activation::relu);
      EXPECT_LT(relative_error(outputs.row(i).transpose(), expected), tolerance) << "row " << i;
      net.forward(inputs.row(i).transpose(), output, sample_workspace);
      EXPECT_LT(relative_error(output, expected), 1e-13) << "row " << i;
    }
  }
}

TEST(MlpRelu, ANegativePreActivationPassesNeitherValueNorGradient) {
  // One hidden unit, weight 1 and bias 0, output weight 1 and bias 0: y = max(0, x).
  Rng rng(22);
  Mlp net({1, 1, 1}, rng, kRelu64);
  net.set_parameters(Eigen::Vector4d(1.0, 0.0, 1.0, 0.0));
  for (double x : {-5.0, -1e-3, 0.0, 1e-3, 2.5}) {
    EXPECT_EQ(net.forward(Eigen::VectorXd::Constant(1, x))[0], std::max(0.0, x)) << "x = " << x;
    MlpBatchWorkspace workspace;
    net.forward_batch(Eigen::MatrixXd::Constant(1, 1, x), workspace);
    Eigen::VectorXd gradient(4);
    net.backward_batch(Eigen::MatrixXd::Ones(1, 1), workspace, gradient);
    // dy/d(W_1, b_1, W_2, b_2) = (x, 1, relu(x), 1) where x > 0; (0, 0, 0, 1) where x <= 0 (PyTorch's 0 at 0).
    const Eigen::Vector4d expected = x > 0 ? Eigen::Vector4d(x, 1.0, x, 1.0) : Eigen::Vector4d(0.0, 0.0, 0.0, 1.0);
    EXPECT_EQ(gradient, Eigen::VectorXd(expected)) << "x = " << x;
  }
}

TEST(MlpRelu, ParameterGradientJvpAndGaussNewtonMatchCentralDifferences) {
  Rng rng(23);
  Mlp net({4, 9, 6, 3}, rng, kRelu64);
  const Eigen::MatrixXd inputs = inputs_away_from_kinks(net, kBatchChunkRows + 5, 1e-3, rng);
  const Eigen::MatrixXd weights = uniform_matrix(inputs.rows(), 3, 2.0, rng);  // L = sum_ij w_ij y_ij
  const Eigen::VectorXd theta = net.parameters();
  const Eigen::VectorXd direction = uniform_matrix(net.num_parameters(), 1, 2.0, rng);
  Mlp probe = net;
  const auto outputs = [&](const Eigen::VectorXd& t) -> Eigen::MatrixXd {
    probe.set_parameters(t);
    MlpBatchWorkspace w;
    return probe.forward_batch(inputs, w);
  };
  const auto loss = [&](const Eigen::VectorXd& t) { return outputs(t).cwiseProduct(weights).sum(); };
  const Eigen::VectorXd expected_gradient = finite_difference_gradient(loss, theta, 1e-6);
  const Eigen::MatrixXd expected_jvp = finite_difference_directional(outputs, theta, direction, 1e-6);
  // Gauss-Newton: sum_i J_i^T (2 J_i v), the gradient of L' = sum_ij (J v)_ij y_ij scaled by 2.
  for (const Dtype dtype : {Dtype::float64, Dtype::float32}) {
    net.set_dtype(dtype);
    const double tolerance = dtype == Dtype::float64 ? 1e-7 : 1e-5;
    MlpBatchWorkspace workspace;
    net.forward_batch(inputs, workspace);
    Eigen::VectorXd gradient(net.num_parameters());
    net.backward_batch(weights, workspace, gradient);
    EXPECT_LT(relative_error(gradient, expected_gradient), tolerance) << to_string(dtype);
    const Eigen::MatrixXd jvp = net.jvp_batch(direction, workspace);
    EXPECT_LT(relative_error(jvp, expected_jvp), tolerance) << to_string(dtype);
    Eigen::VectorXd product(net.num_parameters()), expected_product(net.num_parameters());
    net.gauss_newton_product(direction, 2.0, workspace, product);
    net.backward_batch(2.0 * expected_jvp, workspace, expected_product);
    EXPECT_LT(relative_error(product, expected_product), tolerance) << to_string(dtype);
  }
}

TEST(MlpRelu, InputGradientMatchesCentralDifferences) {
  Rng rng(24);
  Mlp net({5, 9, 7, 2}, rng, kRelu64);
  const Eigen::MatrixXd inputs = inputs_away_from_kinks(net, kBatchChunkRows + 13, 1e-3, rng);
  const Eigen::MatrixXd weights = uniform_matrix(inputs.rows(), 2, 2.0, rng);
  Eigen::MatrixXd expected(inputs.rows(), 5);
  const double h = 1e-6;
  for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
    for (Eigen::Index j = 0; j < 5; ++j) {
      Eigen::VectorXd plus = inputs.row(i).transpose(), minus = plus;
      plus(j) += h;
      minus(j) -= h;
      expected(i, j) = (net.forward(plus) - net.forward(minus)).dot(weights.row(i).transpose()) / (2 * h);
    }
  }
  for (const Dtype dtype : {Dtype::float64, Dtype::float32}) {
    net.set_dtype(dtype);
    MlpBatchWorkspace workspace;
    net.forward_batch(inputs, workspace);
    Eigen::MatrixXd gradient(inputs.rows(), 5);
    net.input_gradient_batch(weights, workspace, gradient);
    EXPECT_LT(relative_error(gradient, expected), dtype == Dtype::float64 ? 1e-7 : 1e-5) << to_string(dtype);
  }
}

TEST(MlpRelu, StreamedPassesEqualTheCachedOnes) {
  Rng rng(25);
  const Mlp net({3, 8, 8, 2}, rng, {.dtype = Dtype::float32, .activation = Activation::relu});
  const Eigen::MatrixXd inputs = uniform_matrix(2 * kBatchChunkRows + 3, 3, 2.0, rng);
  const Eigen::MatrixXd weights = uniform_matrix(inputs.rows(), 2, 2.0, rng);
  MlpBatchWorkspace cached, streamed;
  const Eigen::MatrixXd expected_outputs = net.forward_batch(inputs, cached);
  Eigen::VectorXd expected_gradient(net.num_parameters()), gradient(net.num_parameters());
  net.backward_batch(weights, cached, expected_gradient);
  Eigen::MatrixXd outputs(inputs.rows(), 2);
  net.evaluate_batch(inputs, outputs, streamed);
  EXPECT_EQ(outputs, expected_outputs);
  net.gradient_batch(
      inputs,
      [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& chunk, Eigen::Ref<Eigen::MatrixXd> out) {
        out = weights.middleRows(first, chunk.rows());
      },
      streamed, gradient);
  EXPECT_LT(relative_error(gradient, expected_gradient), 1e-6);
}

}  // namespace
}  // namespace bsg
