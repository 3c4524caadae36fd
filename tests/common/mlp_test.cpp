// The Eigen MLP: initialisation (docs/algorithms.md#networks), flat layout (docs/algorithms.md#networks), forward
// against a hand-written loop, backward and JVP against central differences.
#include "common/mlp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "finite_differences.h"
#include "random_matrices.h"
#include "reference_mlp.h"

namespace bsg {
namespace {

using testing::finite_difference_directional;
using testing::finite_difference_gradient;
using testing::reference_forward;
using testing::relative_error;

using testing::uniform_matrix;

Eigen::VectorXd random_vector(Eigen::Index size, Rng& rng) { return uniform_matrix(size, 1, 2.0, rng); }

TEST(Mlp, ParameterCountMatchesSpecFormula) {
  Rng rng(1);
  const Mlp ant_policy({33, 64, 64, 8}, rng);
  EXPECT_EQ(ant_policy.num_parameters(), 6856);  // docs/algorithms.md#networks example
  EXPECT_EQ(ant_policy.input_size(), 33);
  EXPECT_EQ(ant_policy.output_size(), 8);
}

TEST(Mlp, InitialWeightsAndBiasesLieWithinOneOverSqrtFanIn) {
  Rng rng(2);
  const Mlp net({10, 64, 64, 3}, rng);
  for (int layer = 0; layer < net.num_layers(); ++layer) {
    const double bound = 1.0 / std::sqrt(static_cast<double>(net.layer_sizes()[layer]));
    EXPECT_LE(net.weights(layer).cwiseAbs().maxCoeff(), bound);
    EXPECT_LE(net.bias(layer).cwiseAbs().maxCoeff(), bound);
    EXPECT_GT(net.bias(layer).cwiseAbs().maxCoeff(), 0.0) << "biases are uniform by default (Q1)";
  }
}

TEST(Mlp, InitialWeightVarianceIsOneThirdOverFanIn) {
  Rng rng(3);
  const Mlp net({400, 400, 1}, rng);
  const auto w = net.weights(0);
  const double mean = w.mean();
  const double variance = (w.array() - mean).square().mean();
  EXPECT_NEAR(variance, 1.0 / (3.0 * 400.0), 0.02 / (3.0 * 400.0));
}

TEST(Mlp, ZeroBiasInitGivesZeroBiases) {
  Rng rng(4);
  const Mlp net({5, 64, 64, 2}, rng, MlpOptions{.zero_bias_init = true});
  for (int layer = 0; layer < net.num_layers(); ++layer) EXPECT_EQ(net.bias(layer).norm(), 0.0);
  EXPECT_GT(net.weights(0).norm(), 0.0);
}

TEST(Mlp, SameSeedGivesSameParameters) {
  Rng a(7), b(7), c(8);
  EXPECT_EQ(Mlp({4, 8, 2}, a).parameters(), Mlp({4, 8, 2}, b).parameters());
  Rng d(7);
  EXPECT_NE(Mlp({4, 8, 2}, d).parameters(), Mlp({4, 8, 2}, c).parameters());
}

TEST(Mlp, FlatLayoutIsRowMajorWeightsThenBiasPerLayer) {
  Rng rng(5);
  Mlp net({3, 4, 2}, rng);
  Eigen::VectorXd theta = Eigen::VectorXd::LinSpaced(net.num_parameters(), 0, net.num_parameters() - 1);
  net.set_parameters(theta);
  EXPECT_EQ(net.weights(0)(0, 1), 1.0);   // W_1 row 0, column 1
  EXPECT_EQ(net.weights(0)(1, 0), 3.0);   // W_1 row 1 starts after 3 entries
  EXPECT_EQ(net.bias(0)(0), 12.0);        // b_1 after the 4 x 3 weights
  EXPECT_EQ(net.weights(1)(0, 0), 16.0);  // W_2 after b_1
  EXPECT_EQ(net.bias(1)(1), 25.0);
  EXPECT_EQ(net.num_parameters(), 26);
}

TEST(Mlp, ForwardMatchesLoopImplementationForSampleAndBatch) {
  Rng rng(6);
  const std::vector<int> sizes{5, 7, 6, 3};
  const Mlp net(sizes, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(9, 5, 2.0, rng);
  MlpBatchWorkspace batch_workspace;
  const Eigen::MatrixXd outputs = net.forward_batch(inputs, batch_workspace);
  MlpSampleWorkspace sample_workspace;
  Eigen::VectorXd output(3);
  for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
    const Eigen::VectorXd expected = reference_forward(sizes, net.parameters(), inputs.row(i).transpose());
    net.forward(inputs.row(i).transpose(), output, sample_workspace);
    EXPECT_LT(relative_error(output, expected), 1e-13);
    EXPECT_LT(relative_error(outputs.row(i).transpose(), expected), 1e-13);
  }
}

TEST(Mlp, BackwardMatchesCentralFiniteDifferences) {
  Rng rng(7);
  Mlp net({4, 6, 5, 3}, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(8, 4, 2.0, rng);
  const Eigen::MatrixXd weights = uniform_matrix(8, 3, 2.0, rng);  // L = sum_ij w_ij y_ij
  const Eigen::VectorXd theta = net.parameters();
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  Eigen::VectorXd gradient(net.num_parameters());
  net.backward_batch(weights, workspace, gradient);

  Mlp probe = net;
  const auto loss = [&](const Eigen::VectorXd& t) {
    probe.set_parameters(t);
    MlpBatchWorkspace w;
    return probe.forward_batch(inputs, w).cwiseProduct(weights).sum();
  };
  EXPECT_LT(relative_error(gradient, finite_difference_gradient(loss, theta, 1e-5)), 1e-6);
}

TEST(Mlp, BackwardOverwritesTheGradientAndSumsOverSamples) {
  Rng rng(8);
  const Mlp net({3, 4, 2}, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(2, 3, 2.0, rng);
  const Eigen::MatrixXd weights = uniform_matrix(2, 2, 2.0, rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  Eigen::VectorXd both = Eigen::VectorXd::Constant(net.num_parameters(), 99.0);
  net.backward_batch(weights, workspace, both);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(net.num_parameters());
  for (int i = 0; i < 2; ++i) {
    net.forward_batch(inputs.row(i), workspace);
    Eigen::VectorXd one(net.num_parameters());
    net.backward_batch(weights.row(i), workspace, one);
    sum += one;
  }
  EXPECT_LT(relative_error(both, sum), 1e-14);
}

TEST(Mlp, JacobianVectorProductMatchesCentralFiniteDifferences) {
  Rng rng(9);
  Mlp net({4, 6, 5, 3}, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(8, 4, 2.0, rng);
  const Eigen::VectorXd theta = net.parameters();
  const Eigen::VectorXd direction = random_vector(net.num_parameters(), rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  const Eigen::MatrixXd jvp = net.jvp_batch(direction, workspace);

  Mlp probe = net;
  const auto outputs = [&](const Eigen::VectorXd& t) -> Eigen::MatrixXd {
    probe.set_parameters(t);
    MlpBatchWorkspace w;
    return probe.forward_batch(inputs, w);
  };
  EXPECT_LT(relative_error(jvp, finite_difference_directional(outputs, theta, direction, 1e-5)), 1e-6);
}

TEST(Mlp, JvpAndBackwardAreAdjoint) {
  // <J v, u> = <v, J^T u>: the two hand-written passes describe the same Jacobian.
  Rng rng(10);
  const Mlp net({3, 5, 4, 2}, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(6, 3, 2.0, rng);
  const Eigen::VectorXd v = random_vector(net.num_parameters(), rng);
  const Eigen::MatrixXd u = uniform_matrix(6, 2, 2.0, rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  const double left = net.jvp_batch(v, workspace).cwiseProduct(u).sum();
  Eigen::VectorXd transpose_u(net.num_parameters());
  net.backward_batch(u, workspace, transpose_u);
  EXPECT_NEAR(left, v.dot(transpose_u), 1e-12 * std::abs(left));
}

TEST(Mlp, HiddenActivationIsTanhIncludingSaturation) {
  // One hidden unit with weight 1 and bias 0, output weight 1 and bias 0: y = tanh(x).
  Rng rng(14);
  Mlp net({1, 1, 1}, rng);
  net.set_parameters(Eigen::Vector4d(1.0, 0.0, 1.0, 0.0));
  for (double x : {-800.0, -20.0, -1.5, -1e-3, 0.0, 1e-3, 0.3, 2.0, 20.0, 800.0}) {
    EXPECT_NEAR(net.forward(Eigen::VectorXd::Constant(1, x))[0], std::tanh(x), 1e-15) << "x = " << x;
  }
}

TEST(Mlp, SingleLayerNetworkIsAffine) {
  Rng rng(11);
  Mlp net({2, 3}, rng);
  const Eigen::Vector2d x(0.5, -1.5);
  const Eigen::VectorXd expected = net.weights(0) * x + net.bias(0);
  EXPECT_LT(relative_error(net.forward(x), expected), 1e-15);
}

TEST(Mlp, RejectsBadLayerSizes) {
  Rng rng(12);
  EXPECT_THROW(Mlp({4}, rng), std::invalid_argument);
  EXPECT_THROW(Mlp({4, 0, 2}, rng), std::invalid_argument);
}

TEST(Mlp, WrongSizesGiveExceptionsNamingTheInput) {
  Rng rng(13);
  Mlp net({3, 4, 2}, rng);
  try {
    net.set_parameters(Eigen::VectorXd::Zero(5));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("parameters has 5 entries"), std::string::npos) << e.what();
  }
  MlpSampleWorkspace sample_workspace;
  Eigen::VectorXd output(2);
  EXPECT_THROW(net.forward(Eigen::VectorXd::Zero(4), output, sample_workspace), std::invalid_argument);
  Eigen::VectorXd wrong_output(3);
  EXPECT_THROW(net.forward(Eigen::VectorXd::Zero(3), wrong_output, sample_workspace), std::invalid_argument);
  MlpBatchWorkspace workspace;
  try {
    net.forward_batch(Eigen::MatrixXd::Zero(5, 4), workspace);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("inputs have 4 columns"), std::string::npos) << e.what();
  }
  Eigen::VectorXd gradient(net.num_parameters());
  EXPECT_THROW(net.backward_batch(Eigen::MatrixXd::Zero(5, 2), workspace, gradient), std::logic_error);
  net.forward_batch(Eigen::MatrixXd::Zero(5, 3), workspace);
  EXPECT_THROW(net.backward_batch(Eigen::MatrixXd::Zero(4, 2), workspace, gradient), std::invalid_argument);
  Eigen::VectorXd short_gradient(3);
  EXPECT_THROW(net.backward_batch(Eigen::MatrixXd::Zero(5, 2), workspace, short_gradient), std::invalid_argument);
  EXPECT_THROW(net.jvp_batch(Eigen::VectorXd::Zero(3), workspace), std::invalid_argument);
}

}  // namespace
// --- streamed passes and the Gauss-Newton product (float64) -----------------

TEST(Mlp, StreamedPassesEqualTheCachedOnesOverSeveralChunks) {
  // 300 rows = 2 full chunks of kBatchChunkRows and a partial one.
  Rng rng(21);
  const Mlp net({5, 16, 16, 3}, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(300, 5, 2.0, rng);
  const Eigen::MatrixXd weights = uniform_matrix(300, 3, 2.0, rng);
  MlpBatchWorkspace cached;
  const Eigen::MatrixXd expected_outputs = net.forward_batch(inputs, cached);
  Eigen::VectorXd expected_gradient(net.num_parameters());
  net.backward_batch(weights, cached, expected_gradient);

  MlpBatchWorkspace streamed;
  Eigen::MatrixXd outputs(300, 3);
  net.evaluate_batch(inputs, outputs, streamed);
  EXPECT_LT(relative_error(outputs, expected_outputs), 1e-15);
  Eigen::VectorXd gradient(net.num_parameters());
  Eigen::Index rows_seen = 0;
  net.gradient_batch(
      inputs,
      [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& chunk_outputs,
          Eigen::Ref<Eigen::MatrixXd> output_gradients) {
        EXPECT_EQ(first, rows_seen);
        EXPECT_LT(relative_error(chunk_outputs, expected_outputs.middleRows(first, chunk_outputs.rows())), 1e-15);
        output_gradients = weights.middleRows(first, chunk_outputs.rows());
        rows_seen += chunk_outputs.rows();
      },
      streamed, gradient);
  EXPECT_EQ(rows_seen, 300);
  EXPECT_LT(relative_error(gradient, expected_gradient), 1e-14);
  // A streamed pass leaves no cached forward pass behind.
  EXPECT_THROW(net.backward_batch(weights, streamed, gradient), std::logic_error);
}

TEST(Mlp, GaussNewtonProductIsJacobianTransposeTimesScaledJacobianProduct) {
  // sum_i J_i^T (s J_i v), with J_i v by finite differences and J_i^T u by
  // finite differences of the scalar <y(theta), u>.
  Rng rng(22);
  Mlp net({4, 6, 5, 2}, rng);
  const Eigen::MatrixXd inputs = uniform_matrix(150, 4, 2.0, rng);
  const Eigen::VectorXd theta = net.parameters();
  const Eigen::VectorXd v = random_vector(net.num_parameters(), rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(inputs, workspace);
  Eigen::VectorXd product(net.num_parameters());
  net.gauss_newton_product(v, 0.3, workspace, product);

  Mlp probe = net;
  const auto outputs = [&](const Eigen::VectorXd& t) -> Eigen::MatrixXd {
    probe.set_parameters(t);
    MlpBatchWorkspace w;
    return probe.forward_batch(inputs, w);
  };
  const Eigen::MatrixXd u = 0.3 * finite_difference_directional(outputs, theta, v, 1e-5);
  const auto weighted = [&](const Eigen::VectorXd& t) { return outputs(t).cwiseProduct(u).sum(); };
  EXPECT_LT(relative_error(product, finite_difference_gradient(weighted, theta, 1e-5)), 1e-6);
}

// --- float32 against the float64 oracle -------------------------------------
// The same parameters and inputs in both dtypes; float32 rounds parameters,
// inputs and every intermediate to 24 bits (relative 6e-8), and sums of a few
// hundred terms of both signs lose a few more digits: 1e-5 relative to the
// result's norm is what single precision can promise here, and an error in
// the float32 code (a wrong index, a missing term) is of order 1.

TEST(MlpFloat32, EveryBatchPassMatchesFloat64WithinSinglePrecision) {
  Rng rng(23);
  Mlp net64({8, 64, 64, 2}, rng);
  Mlp net32 = net64;
  net32.set_dtype(Dtype::float32);
  const Eigen::MatrixXd inputs = uniform_matrix(300, 8, 2.0, rng);
  const Eigen::MatrixXd weights = uniform_matrix(300, 2, 2.0, rng);
  const Eigen::VectorXd v = random_vector(net64.num_parameters(), rng);
  MlpBatchWorkspace w64, w32;

  const Eigen::MatrixXd out64 = net64.forward_batch(inputs, w64);
  const Eigen::MatrixXd out32 = net32.forward_batch(inputs, w32);
  EXPECT_LT(relative_error(out32, out64), 1e-5);
  EXPECT_GT(relative_error(out32, out64), 0.0);  // it does compute in single precision

  Eigen::VectorXd g64(net64.num_parameters()), g32(net64.num_parameters());
  net64.backward_batch(weights, w64, g64);
  net32.backward_batch(weights, w32, g32);
  EXPECT_LT(relative_error(g32, g64), 1e-5);

  EXPECT_LT(relative_error(net32.jvp_batch(v, w32), net64.jvp_batch(v, w64)), 1e-5);

  Eigen::VectorXd p64(net64.num_parameters()), p32(net64.num_parameters());
  net64.gauss_newton_product(v, 0.5, w64, p64);
  net32.gauss_newton_product(v, 0.5, w32, p32);
  EXPECT_LT(relative_error(p32, p64), 1e-5);

  Eigen::MatrixXd streamed32(300, 2);
  net32.evaluate_batch(inputs, streamed32, w32);
  EXPECT_EQ(streamed32, out32);  // same chunks, same arithmetic
  net32.gradient_batch(
      inputs,
      [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& chunk,
          Eigen::Ref<Eigen::MatrixXd> output_gradients) { output_gradients = weights.middleRows(first, chunk.rows()); },
      w32, g32);
  EXPECT_LT(relative_error(g32, g64), 1e-5);
}

TEST(MlpFloat32, TanhSaturatesAndKeepsRelativeAccuracyNearZero) {
  Rng rng(24);
  Mlp net({1, 1, 1}, rng, MlpOptions{.zero_bias_init = false, .dtype = Dtype::float32});
  net.set_parameters(Eigen::Vector4d(1.0, 0.0, 1.0, 0.0));  // y = tanh(x)
  Eigen::MatrixXd inputs(10, 1);
  inputs << -800.0, -20.0, -1.5, -1e-3, 0.0, 1e-6, 0.3, 2.0, 20.0, 800.0;
  MlpBatchWorkspace workspace;
  const Eigen::MatrixXd outputs = net.forward_batch(inputs, workspace);
  for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
    const double expected = std::tanh(inputs(i, 0));
    EXPECT_NEAR(outputs(i, 0), expected, 5e-7 * std::abs(expected) + 1e-37) << "x = " << inputs(i, 0);
  }
}

TEST(MlpFloat32, ACachedPassOfTheOtherDtypeIsNotReused) {
  Rng rng(25);
  Mlp net({3, 4, 2}, rng);
  MlpBatchWorkspace workspace;
  net.forward_batch(Eigen::MatrixXd::Zero(5, 3), workspace);
  net.set_dtype(Dtype::float32);
  Eigen::VectorXd gradient(net.num_parameters());
  EXPECT_THROW(net.backward_batch(Eigen::MatrixXd::Zero(5, 2), workspace, gradient), std::logic_error);
}

}  // namespace bsg
