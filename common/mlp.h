// A fully connected network on Eigen with hand-written backward pass and
// Jacobian-vector product (docs/algorithms.md#networks). Hidden layers use tanh, the output layer is
// the identity; layer sizes come from the caller, e.g. {d_o, 64, 64, d_a}.
//
// Parameters live in one flat vector in the order of docs/algorithms.md#networks:
// [W_1, b_1, W_2, b_2, ..., W_L, b_L], every W_l of shape (out, in) flattened
// row-major. Gradients, JVP directions and set/get all use this layout.
//
// Batches hold one sample per row (N x in). The batch functions cache what the
// backward pass and the JVP need in an MlpBatchWorkspace, whose buffers are
// reused while the batch size stays the same (no allocation per call).
//
// Parameters:
//   layer_sizes      [in, hidden..., out], at least two entries, all positive.
//   zero_bias_init   false (default): biases ~ U(-1/sqrt(in), 1/sqrt(in)) as the
//                    original code does (quirk Q1); true: zero biases as the report says.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "common/random.h"

namespace bsg {

using RowMajorMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct MlpInitOptions {
  bool zero_bias_init = false;
};

// Buffers for one-sample forward passes: one vector per layer output.
struct MlpSampleWorkspace {
  std::vector<Eigen::VectorXd> layer_outputs;
};

// Buffers for batch passes, sized by Mlp::forward_batch.
struct MlpBatchWorkspace {
  Eigen::MatrixXd input;                        // N x in, copy of the last forward input
  std::vector<Eigen::MatrixXd> layer_outputs;   // A_l, N x width_l (after activation)
  std::vector<Eigen::MatrixXd> layer_tangents;  // JVP: dA_l for the last direction
  std::vector<Eigen::MatrixXd> layer_deltas;    // backward: dL/dZ_l
  Eigen::Index rows() const { return input.rows(); }
};

class Mlp {
 public:
  // Draws the initial parameters from `rng` (weights, then bias, layer by layer).
  Mlp(std::vector<int> layer_sizes, Rng& rng, MlpInitOptions options = {});

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

  // Batch forward: returns the N x out outputs, stored in `workspace`.
  const Eigen::MatrixXd& forward_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                                       MlpBatchWorkspace& workspace) const;

  // Parameter gradient sum_i (dL/dy_i)^T dy_i/dtheta for the batch of the last
  // forward_batch on `workspace`. `output_gradients` is N x out (dL/doutput per
  // sample, any 1/N already included). Overwrites `parameter_gradient`.
  void backward_batch(const Eigen::Ref<const Eigen::MatrixXd>& output_gradients,
                      MlpBatchWorkspace& workspace,
                      Eigen::Ref<Eigen::VectorXd> parameter_gradient) const;

  // Jacobian-vector product: row i is (dy_i/dtheta) v for the batch of the last
  // forward_batch on `workspace`. Returns the N x out tangents, stored in `workspace`.
  const Eigen::MatrixXd& jvp_batch(const Eigen::Ref<const Eigen::VectorXd>& direction,
                                   MlpBatchWorkspace& workspace) const;

 private:
  void check_batch_workspace(const MlpBatchWorkspace& workspace, const char* where) const;

  std::vector<int> layer_sizes_;
  std::vector<Eigen::Index> weight_offsets_;
  std::vector<Eigen::Index> bias_offsets_;
  Eigen::VectorXd parameters_;
};

}  // namespace bsg
