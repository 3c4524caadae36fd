// A fully connected network on Eigen with hand-written backward pass and
// Jacobian-vector product (docs/algorithms.md#networks). Hidden layers use tanh (or relu,
// MlpOptions::activation), the output layer is the identity; layer sizes come from the caller,
// e.g. {d_o, 64, 64, d_a}.
//
// Parameters live in one flat vector in the order of docs/algorithms.md#networks:
// [W_1, b_1, W_2, b_2, ..., W_L, b_L], every W_l of shape (out, in) flattened
// row-major. Gradients, JVP directions and set/get all use this layout.
//
// Batches hold one sample per row (N x in). Batch arithmetic runs in the
// network's dtype (float32 or float64; common/dtype.h) over chunks of
// kBatchChunkRows rows; inputs, outputs and parameter vectors are double in
// both cases (float32 rounds the parameters once per call). Two kinds of pass:
//   - cached (forward_batch, then backward_batch / jvp_batch /
//     gauss_newton_product): the forward activations of all N rows are kept
//     in the workspace for the passes that follow (the Fisher-vector product
//     reuses them for every CG iteration);
//   - streamed (evaluate_batch, gradient_batch): one chunk's activations at a
//     time, so memory does not grow with N.
// Workspace buffers are reused while the sizes stay the same (no allocation per call).
//
// Parameters:
//   layer_sizes      [in, hidden..., out], at least two entries, all positive.
//   zero_bias_init   false (default): biases ~ U(-1/sqrt(in), 1/sqrt(in)) as the
//                    original code does (quirk Q1); true: zero biases as the report says.
//   dtype            float64 (default here; the run config chooses, see configs/README.md).
//   activation       tanh (default) or relu, of every hidden layer.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "common/activation.h"
#include "common/dtype.h"
#include "common/random.h"

namespace bsg {

using RowMajorMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct MlpOptions {
  bool zero_bias_init = false;
  Dtype dtype = Dtype::float64;  // arithmetic of the batch passes
  Activation activation = Activation::tanh;  // of the hidden layers
};

// Rows per chunk of a batch pass: every matrix product then fits Eigen's
// stack-allocated blocking buffers (no heap allocation per call), and a
// chunk's activations stay in cache between layers.
inline constexpr Eigen::Index kBatchChunkRows = 128;

// Buffers for one-sample forward passes: one vector per layer output.
struct MlpSampleWorkspace {
  std::vector<Eigen::VectorXd> layer_outputs;
};

// The batch buffers of one dtype.
template <typename Scalar>
struct MlpBatchBuffers {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  Matrix input;                        // cached: N x in; streamed: one chunk
  std::vector<Matrix> layer_outputs;   // A_l after activation; cached: N rows, streamed: one chunk
  std::vector<Matrix> layer_tangents;  // JVP dA_l of one chunk
  std::vector<Matrix> layer_deltas;    // backward dL/dZ_l of one chunk
  Matrix input_gradient;               // dL/dX of one chunk (input_gradient_batch)
  Vector parameters;                   // float32: the parameters rounded for this call
  Vector direction;                    // float32: the JVP direction rounded
  Vector gradient;                     // parameter gradient accumulated over the chunks
};

// Buffers for batch passes, sized by the Mlp's batch functions.
struct MlpBatchWorkspace {
  MlpBatchBuffers<double> f64;
  MlpBatchBuffers<float> f32;
  Eigen::MatrixXd outputs;           // N x out: outputs of the last forward or evaluate pass
  Eigen::MatrixXd tangents;          // N x out: the last jvp_batch
  Eigen::MatrixXd chunk_outputs;     // gradient_batch: one chunk's outputs, for the callback
  Eigen::MatrixXd chunk_gradients;   // gradient_batch: dL/dy of one chunk, from the callback
  Eigen::Index cached_rows = -1;     // rows of the cached forward pass, -1 if none
  Dtype cached_dtype = Dtype::float64;
  Eigen::Index rows() const { return cached_rows; }
};

// gradient_batch's callback: given the outputs of rows [first_row, first_row +
// outputs.rows()), writes dL/dy of those rows into output_gradients (same shape).
using OutputGradientFunction =
    std::function<void(Eigen::Index first_row, const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                       Eigen::Ref<Eigen::MatrixXd> output_gradients)>;

class Mlp {
 public:
  // Draws the initial parameters from `rng` (weights, then bias, layer by layer).
  Mlp(std::vector<int> layer_sizes, Rng& rng, MlpOptions options = {});

  Dtype dtype() const { return dtype_; }
  void set_dtype(Dtype dtype) { dtype_ = dtype; }
  Activation activation() const { return activation_; }

  int input_size() const { return layer_sizes_.front(); }
  int output_size() const { return layer_sizes_.back(); }
  int num_layers() const { return static_cast<int>(layer_sizes_.size()) - 1; }
  const std::vector<int>& layer_sizes() const { return layer_sizes_; }
  Eigen::Index num_parameters() const { return parameters_.size(); }

  const Eigen::VectorXd& parameters() const { return parameters_; }
  void set_parameters(const Eigen::Ref<const Eigen::VectorXd>& parameters);
  // Writable view of fixed size (for optimisers that update in place).
  Eigen::Map<Eigen::VectorXd> mutable_parameters() {
    return Eigen::Map<Eigen::VectorXd>(parameters_.data(), parameters_.size());
  }

  // Views of layer `layer` (0-based) inside the flat parameter vector.
  Eigen::Map<const RowMajorMatrixXd> weights(int layer) const;
  Eigen::Map<const Eigen::VectorXd> bias(int layer) const;
  Eigen::Index weight_offset(int layer) const { return weight_offsets_.at(layer); }
  Eigen::Index bias_offset(int layer) const { return bias_offsets_.at(layer); }

  // One sample, no allocation once `workspace` has been sized (the first call sizes it).
  void forward(const Eigen::Ref<const Eigen::VectorXd>& input, Eigen::Ref<Eigen::VectorXd> output,
               MlpSampleWorkspace& workspace) const;
  // Convenience form for tests and evaluation (allocates).
  Eigen::VectorXd forward(const Eigen::Ref<const Eigen::VectorXd>& input) const;

  // Cached batch forward: returns the N x out outputs (in `workspace`) and
  // keeps every activation for the passes below.
  const Eigen::MatrixXd& forward_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                                       MlpBatchWorkspace& workspace) const;

  // Parameter gradient sum_i (dL/dy_i)^T dy_i/dtheta for the batch of the last
  // forward_batch on `workspace`. `output_gradients` is N x out (dL/doutput per
  // sample, any 1/N already included). Overwrites `parameter_gradient`.
  void backward_batch(const Eigen::Ref<const Eigen::MatrixXd>& output_gradients,
                      MlpBatchWorkspace& workspace,
                      Eigen::Ref<Eigen::VectorXd> parameter_gradient) const;

  // Input gradient: row i is (dL/dy_i)^T dy_i/dx_i, the gradient of the loss
  // with respect to sample i's input (a critic's dQ/da: the off-policy actor
  // losses, algos/off_policy/), for the batch of the last forward_batch on
  // `workspace`. `output_gradients` is N x out; `input_gradient` (N x in) is
  // overwritten. The parameters' gradient is not formed.
  void input_gradient_batch(const Eigen::Ref<const Eigen::MatrixXd>& output_gradients, MlpBatchWorkspace& workspace,
                            Eigen::Ref<Eigen::MatrixXd> input_gradient) const;

  // Jacobian-vector product: row i is (dy_i/dtheta) v for the batch of the last
  // forward_batch on `workspace`. Returns the N x out tangents, stored in `workspace`.
  const Eigen::MatrixXd& jvp_batch(const Eigen::Ref<const Eigen::VectorXd>& direction,
                                   MlpBatchWorkspace& workspace) const;

  // Gauss-Newton product sum_i J_i^T (scale J_i v), J_i = dy_i/dtheta, for the
  // batch of the last forward_batch: jvp_batch then backward_batch in one pass
  // per chunk, without whole-batch tangents. Overwrites `product`.
  void gauss_newton_product(const Eigen::Ref<const Eigen::VectorXd>& direction, double scale,
                            MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::VectorXd> product) const;

  // Streamed forward: outputs (N x out) of `inputs`, keeping no activations
  // (drops any cached pass of `workspace`).
  void evaluate_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs, Eigen::Ref<Eigen::MatrixXd> outputs,
                      MlpBatchWorkspace& workspace) const;

  // Streamed gradient: for each chunk, the forward pass, `output_gradient` for
  // its rows, and the backward pass; overwrites `parameter_gradient` with
  // sum_i (dL/dy_i)^T dy_i/dtheta. Drops any cached pass of `workspace`.
  void gradient_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs, const OutputGradientFunction& output_gradient,
                      MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::VectorXd> parameter_gradient) const;

 private:
  void check_batch_workspace(const MlpBatchWorkspace& workspace, const char* where) const;
  void check_parameter_vector(Eigen::Index size, const char* what) const;

  std::vector<int> layer_sizes_;
  std::vector<Eigen::Index> weight_offsets_;
  std::vector<Eigen::Index> bias_offsets_;
  Eigen::VectorXd parameters_;
  Dtype dtype_ = Dtype::float64;
  Activation activation_ = Activation::tanh;
};

}  // namespace bsg
