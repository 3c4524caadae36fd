#include "common/mlp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace bsg {
namespace {

std::string sizes_to_string(const std::vector<int>& sizes) {
  std::string text = "[";
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    text += (i ? ", " : "") + std::to_string(sizes[i]);
  }
  return text + "]";
}

// tanh in place. Doubles: tanh(x) = 1 - 2 / (exp(2x) + 1); Eigen vectorises
// exp but not tanh for doubles, and this form is about 3x faster and within
// 4e-16 (absolute) of std::tanh, saturating cleanly to +-1 (exp overflow gives
// 1 - 0). Floats: Eigen's own vectorised rational approximation, which keeps
// the relative accuracy near 0 that the exp form loses.
template <typename Derived>
void tanh_in_place(Eigen::DenseBase<Derived>& values) {
  using Scalar = typename Derived::Scalar;
  if constexpr (std::is_same_v<Scalar, float>) {
    values.derived().array() = values.derived().array().tanh();
  } else {
    values.derived().array() = Scalar(1) - Scalar(2) / ((Scalar(2) * values.derived().array()).exp() + Scalar(1));
  }
}

// A = activation(Z) in place, for a hidden layer.
template <typename Derived>
void activate_in_place(Eigen::DenseBase<Derived>& values, Activation activation) {
  if (activation == Activation::relu) {
    values.derived().array() = values.derived().array().max(typename Derived::Scalar(0));
  } else {
    tanh_in_place(values);
  }
}

// gradients *= activation'(Z), written with the layer's output A = activation(Z):
// tanh' = 1 - A^2; relu' = 1 where A > 0, else 0 (0 at Z = 0, as PyTorch's).
template <typename Gradients, typename Outputs>
void multiply_by_derivative(Eigen::DenseBase<Gradients>& gradients, const Eigen::DenseBase<Outputs>& outputs,
                            Activation activation) {
  using Scalar = typename Gradients::Scalar;
  if (activation == Activation::relu) {
    gradients.derived().array() =
        (outputs.derived().array() > Scalar(0)).select(gradients.derived().array(), Scalar(0));
  } else {
    gradients.derived().array() *= Scalar(1) - outputs.derived().array().square();
  }
}

template <typename Matrix>
void resize_if_needed(Matrix& matrix, Eigen::Index rows, Eigen::Index cols) {
  if (matrix.rows() != rows || matrix.cols() != cols) matrix.resize(rows, cols);
}

template <typename Vector>
void resize_vector_if_needed(Vector& vector, Eigen::Index size) {
  if (vector.size() != size) vector.resize(size);
}

template <typename Scalar>
using RowMajorMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <typename Scalar>
using ColumnVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

// The network's layout over a flat parameter (or direction, or gradient)
// vector of one dtype.
template <typename Scalar>
struct FlatLayout {
  const Mlp& net;
  int layers() const { return net.num_layers(); }
  Eigen::Index in(int layer) const { return net.layer_sizes()[layer]; }
  Eigen::Index out(int layer) const { return net.layer_sizes()[layer + 1]; }
  Eigen::Map<const RowMajorMatrix<Scalar>> weights(const Scalar* flat, int layer) const {
    return Eigen::Map<const RowMajorMatrix<Scalar>>(flat + net.weight_offset(layer), out(layer), in(layer));
  }
  Eigen::Map<RowMajorMatrix<Scalar>> weights(Scalar* flat, int layer) const {
    return Eigen::Map<RowMajorMatrix<Scalar>>(flat + net.weight_offset(layer), out(layer), in(layer));
  }
  Eigen::Map<const ColumnVector<Scalar>> bias(const Scalar* flat, int layer) const {
    return Eigen::Map<const ColumnVector<Scalar>>(flat + net.bias_offset(layer), out(layer));
  }
  Eigen::Map<ColumnVector<Scalar>> bias(Scalar* flat, int layer) const {
    return Eigen::Map<ColumnVector<Scalar>>(flat + net.bias_offset(layer), out(layer));
  }
};

template <typename Scalar>
MlpBatchBuffers<Scalar>& buffers_of(MlpBatchWorkspace& workspace);
template <>
MlpBatchBuffers<double>& buffers_of<double>(MlpBatchWorkspace& workspace) { return workspace.f64; }
template <>
MlpBatchBuffers<float>& buffers_of<float>(MlpBatchWorkspace& workspace) { return workspace.f32; }

// The parameters in the pass's dtype: a view for double, a rounded copy for float.
template <typename Scalar>
const Scalar* parameters_in(const Mlp& net, MlpBatchBuffers<Scalar>& buffers) {
  if constexpr (std::is_same_v<Scalar, double>) {
    return net.parameters().data();
  } else {
    resize_vector_if_needed(buffers.parameters, net.num_parameters());
    buffers.parameters = net.parameters().template cast<Scalar>();
    return buffers.parameters.data();
  }
}

// Sizes the per-layer lists; `activation_rows` rows for layer_outputs, one
// chunk for tangents and deltas.
template <typename Scalar>
void size_buffers(const Mlp& net, MlpBatchBuffers<Scalar>& buffers, Eigen::Index activation_rows) {
  const std::size_t layers = static_cast<std::size_t>(net.num_layers());
  if (buffers.layer_outputs.size() != layers) buffers.layer_outputs.resize(layers);
  if (buffers.layer_tangents.size() != layers) buffers.layer_tangents.resize(layers);
  if (buffers.layer_deltas.size() != layers) buffers.layer_deltas.resize(layers);
  for (int layer = 0; layer < net.num_layers(); ++layer) {
    resize_if_needed(buffers.layer_outputs[layer], activation_rows, net.layer_sizes()[layer + 1]);
  }
}

// A_l for every layer of rows [start, start + length) of buffers.input into
// the same rows of buffers.layer_outputs.
template <typename Scalar>
void forward_rows(const FlatLayout<Scalar>& layout, const Scalar* parameters, MlpBatchBuffers<Scalar>& buffers,
                  Eigen::Index start, Eigen::Index length) {
  for (int layer = 0; layer < layout.layers(); ++layer) {
    const auto& previous = layer == 0 ? buffers.input : buffers.layer_outputs[layer - 1];
    auto a = buffers.layer_outputs[layer].middleRows(start, length);
    a.noalias() = previous.middleRows(start, length) * layout.weights(parameters, layer).transpose();  // Z = A W^T + 1 b^T
    a.rowwise() += layout.bias(parameters, layer).transpose();
    if (layer + 1 < layout.layers()) activate_in_place(a, layout.net.activation());
  }
}

// Backward pass of rows [start, start + length) whose dL/dZ_L the caller has
// written into the top `length` rows of buffers.layer_deltas.back();
// accumulates into buffers.gradient.
template <typename Scalar>
void backward_rows(const FlatLayout<Scalar>& layout, const Scalar* parameters, MlpBatchBuffers<Scalar>& buffers,
                   Eigen::Index start, Eigen::Index length) {
  Scalar* gradient = buffers.gradient.data();
  for (int layer = layout.layers() - 1; layer >= 0; --layer) {
    const auto delta = buffers.layer_deltas[layer].topRows(length);
    const auto& previous_full = layer == 0 ? buffers.input : buffers.layer_outputs[layer - 1];
    const auto previous = previous_full.middleRows(start, length);
    layout.weights(gradient, layer).noalias() += delta.transpose() * previous;  // dL/dW = sum delta^T A_{l-1}
    layout.bias(gradient, layer) += delta.colwise().sum().transpose();
    if (layer > 0) {
      auto delta_previous = buffers.layer_deltas[layer - 1].topRows(length);
      delta_previous.noalias() = delta * layout.weights(parameters, layer);
      multiply_by_derivative(delta_previous, previous, layout.net.activation());
    }
  }
}

// JVP of rows [start, start + length) along `direction` into the top `length`
// rows of buffers.layer_tangents.
template <typename Scalar>
void jvp_rows(const FlatLayout<Scalar>& layout, const Scalar* parameters, const Scalar* direction,
              MlpBatchBuffers<Scalar>& buffers, Eigen::Index start, Eigen::Index length) {
  for (int layer = 0; layer < layout.layers(); ++layer) {
    auto tangent = buffers.layer_tangents[layer].topRows(length);
    const auto& previous = layer == 0 ? buffers.input : buffers.layer_outputs[layer - 1];
    // dZ_l = dA_{l-1} W_l^T + A_{l-1} dW_l^T + 1 db_l^T
    tangent.noalias() = previous.middleRows(start, length) * layout.weights(direction, layer).transpose();
    if (layer > 0) {
      tangent.noalias() += buffers.layer_tangents[layer - 1].topRows(length) * layout.weights(parameters, layer).transpose();
    }
    tangent.rowwise() += layout.bias(direction, layer).transpose();
    if (layer + 1 < layout.layers()) {
      // dA = activation'(Z) dZ
      multiply_by_derivative(tangent, buffers.layer_outputs[layer].middleRows(start, length), layout.net.activation());
    }
  }
}

template <typename Scalar>
void size_chunk_buffers(const Mlp& net, MlpBatchBuffers<Scalar>& buffers, bool tangents) {
  for (int layer = 0; layer < net.num_layers(); ++layer) {
    resize_if_needed(buffers.layer_deltas[layer], kBatchChunkRows, net.layer_sizes()[layer + 1]);
    if (tangents) resize_if_needed(buffers.layer_tangents[layer], kBatchChunkRows, net.layer_sizes()[layer + 1]);
  }
  resize_vector_if_needed(buffers.gradient, net.num_parameters());
  buffers.gradient.setZero();
}

template <typename Scalar>
const Scalar* direction_in(const Eigen::Ref<const Eigen::VectorXd>& direction, MlpBatchBuffers<Scalar>& buffers) {
  if constexpr (std::is_same_v<Scalar, double>) {
    return direction.data();
  } else {
    resize_vector_if_needed(buffers.direction, direction.size());
    buffers.direction = direction.template cast<Scalar>();
    return buffers.direction.data();
  }
}

template <typename Scalar>
void cached_forward(const Mlp& net, const Eigen::Ref<const Eigen::MatrixXd>& inputs, MlpBatchWorkspace& workspace) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  const Eigen::Index rows = inputs.rows();
  resize_if_needed(buffers.input, rows, net.input_size());
  buffers.input = inputs.template cast<Scalar>();
  size_buffers(net, buffers, rows);
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    forward_rows(layout, parameters, buffers, start, std::min(kBatchChunkRows, rows - start));
  }
  resize_if_needed(workspace.outputs, rows, net.output_size());
  workspace.outputs = buffers.layer_outputs.back().template cast<double>();
}

template <typename Scalar>
void cached_backward(const Mlp& net, const Eigen::Ref<const Eigen::MatrixXd>& output_gradients,
                     MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::VectorXd> parameter_gradient) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  const Eigen::Index rows = workspace.cached_rows;
  size_chunk_buffers(net, buffers, false);
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    const Eigen::Index length = std::min(kBatchChunkRows, rows - start);
    // identity output: dL/dZ_L = dL/dy
    buffers.layer_deltas.back().topRows(length) = output_gradients.middleRows(start, length).template cast<Scalar>();
    backward_rows(layout, parameters, buffers, start, length);
  }
  parameter_gradient = buffers.gradient.template cast<double>();
}

// dL/dX of rows [start, start + length) whose dL/dZ_L the caller has written
// into the top `length` rows of buffers.layer_deltas.back(): the backward pass
// of the deltas alone, then dL/dX = delta_1 W_1.
template <typename Scalar>
void input_gradient_rows(const FlatLayout<Scalar>& layout, const Scalar* parameters, MlpBatchBuffers<Scalar>& buffers,
                         Eigen::Index start, Eigen::Index length,
                         Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& input_gradient) {
  for (int layer = layout.layers() - 1; layer > 0; --layer) {
    const auto delta = buffers.layer_deltas[layer].topRows(length);
    auto delta_previous = buffers.layer_deltas[layer - 1].topRows(length);
    delta_previous.noalias() = delta * layout.weights(parameters, layer);
    multiply_by_derivative(delta_previous, buffers.layer_outputs[layer - 1].middleRows(start, length),
                           layout.net.activation());
  }
  input_gradient.topRows(length).noalias() = buffers.layer_deltas[0].topRows(length) * layout.weights(parameters, 0);
}

template <typename Scalar>
void cached_input_gradient(const Mlp& net, const Eigen::Ref<const Eigen::MatrixXd>& output_gradients,
                           MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::MatrixXd> input_gradient) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  const Eigen::Index rows = workspace.cached_rows;
  for (int layer = 0; layer < net.num_layers(); ++layer) {
    resize_if_needed(buffers.layer_deltas[layer], kBatchChunkRows, net.layer_sizes()[layer + 1]);
  }
  auto& chunk = buffers.input_gradient;
  resize_if_needed(chunk, kBatchChunkRows, net.input_size());
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    const Eigen::Index length = std::min(kBatchChunkRows, rows - start);
    buffers.layer_deltas.back().topRows(length) = output_gradients.middleRows(start, length).template cast<Scalar>();
    input_gradient_rows(layout, parameters, buffers, start, length, chunk);
    input_gradient.middleRows(start, length) = chunk.topRows(length).template cast<double>();
  }
}

template <typename Scalar>
void cached_jvp(const Mlp& net, const Eigen::Ref<const Eigen::VectorXd>& direction, MlpBatchWorkspace& workspace) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  const Eigen::Index rows = workspace.cached_rows;
  size_chunk_buffers(net, buffers, true);
  resize_if_needed(workspace.tangents, rows, net.output_size());
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  const Scalar* direction_data = direction_in(direction, buffers);
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    const Eigen::Index length = std::min(kBatchChunkRows, rows - start);
    jvp_rows(layout, parameters, direction_data, buffers, start, length);
    workspace.tangents.middleRows(start, length) = buffers.layer_tangents.back().topRows(length).template cast<double>();
  }
}

template <typename Scalar>
void cached_gauss_newton(const Mlp& net, const Eigen::Ref<const Eigen::VectorXd>& direction, double scale,
                         MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::VectorXd> product) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  const Eigen::Index rows = workspace.cached_rows;
  size_chunk_buffers(net, buffers, true);
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  const Scalar* direction_data = direction_in(direction, buffers);
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    const Eigen::Index length = std::min(kBatchChunkRows, rows - start);
    jvp_rows(layout, parameters, direction_data, buffers, start, length);
    // dL/dy_i = scale J_i v
    buffers.layer_deltas.back().topRows(length) = static_cast<Scalar>(scale) * buffers.layer_tangents.back().topRows(length);
    backward_rows(layout, parameters, buffers, start, length);
  }
  product = buffers.gradient.template cast<double>();
}

// Streamed passes: buffers.input and layer_outputs hold one chunk (start 0).
template <typename Scalar>
void prepare_stream(const Mlp& net, MlpBatchWorkspace& workspace, MlpBatchBuffers<Scalar>& buffers) {
  workspace.cached_rows = -1;
  resize_if_needed(buffers.input, kBatchChunkRows, net.input_size());
  size_buffers(net, buffers, kBatchChunkRows);
}

template <typename Scalar>
void streamed_evaluate(const Mlp& net, const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                       Eigen::Ref<Eigen::MatrixXd> outputs, MlpBatchWorkspace& workspace) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  prepare_stream(net, workspace, buffers);
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  const Eigen::Index rows = inputs.rows();
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    const Eigen::Index length = std::min(kBatchChunkRows, rows - start);
    buffers.input.topRows(length) = inputs.middleRows(start, length).template cast<Scalar>();
    forward_rows(layout, parameters, buffers, 0, length);
    outputs.middleRows(start, length) = buffers.layer_outputs.back().topRows(length).template cast<double>();
  }
}

template <typename Scalar>
void streamed_gradient(const Mlp& net, const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                       const OutputGradientFunction& output_gradient, MlpBatchWorkspace& workspace,
                       Eigen::Ref<Eigen::VectorXd> parameter_gradient) {
  MlpBatchBuffers<Scalar>& buffers = buffers_of<Scalar>(workspace);
  prepare_stream(net, workspace, buffers);
  size_chunk_buffers(net, buffers, false);
  resize_if_needed(workspace.chunk_outputs, kBatchChunkRows, net.output_size());
  resize_if_needed(workspace.chunk_gradients, kBatchChunkRows, net.output_size());
  const FlatLayout<Scalar> layout{net};
  const Scalar* parameters = parameters_in(net, buffers);
  const Eigen::Index rows = inputs.rows();
  for (Eigen::Index start = 0; start < rows; start += kBatchChunkRows) {
    const Eigen::Index length = std::min(kBatchChunkRows, rows - start);
    buffers.input.topRows(length) = inputs.middleRows(start, length).template cast<Scalar>();
    forward_rows(layout, parameters, buffers, 0, length);
    workspace.chunk_outputs.topRows(length) = buffers.layer_outputs.back().topRows(length).template cast<double>();
    output_gradient(start, workspace.chunk_outputs.topRows(length), workspace.chunk_gradients.topRows(length));
    buffers.layer_deltas.back().topRows(length) = workspace.chunk_gradients.topRows(length).template cast<Scalar>();
    backward_rows(layout, parameters, buffers, 0, length);
  }
  parameter_gradient = buffers.gradient.template cast<double>();
}

}  // namespace

Mlp::Mlp(std::vector<int> layer_sizes, Rng& rng, MlpOptions options)
    : layer_sizes_(std::move(layer_sizes)), dtype_(options.dtype), activation_(options.activation) {
  if (layer_sizes_.size() < 2) {
    throw std::invalid_argument("Mlp: layer_sizes " + sizes_to_string(layer_sizes_) +
                                " needs at least an input and an output size");
  }
  for (int size : layer_sizes_) {
    if (size <= 0) {
      throw std::invalid_argument("Mlp: layer_sizes " + sizes_to_string(layer_sizes_) +
                                  " must all be positive");
    }
  }
  Eigen::Index offset = 0;
  for (int layer = 0; layer < num_layers(); ++layer) {
    const Eigen::Index in = layer_sizes_[layer];
    const Eigen::Index out = layer_sizes_[layer + 1];
    weight_offsets_.push_back(offset);
    offset += out * in;
    bias_offsets_.push_back(offset);
    offset += out;
  }
  parameters_.resize(offset);
  // Kaiming-uniform with a = sqrt(5): bound = 1/sqrt(fan_in) (docs/algorithms.md#networks); the
  // biases keep PyTorch's default, the same bound (Q1), unless zero_bias_init.
  for (int layer = 0; layer < num_layers(); ++layer) {
    const Eigen::Index in = layer_sizes_[layer];
    const Eigen::Index out = layer_sizes_[layer + 1];
    const double bound = 1.0 / std::sqrt(static_cast<double>(in));
    for (Eigen::Index i = 0; i < out * in; ++i) {
      parameters_[weight_offsets_[layer] + i] = uniform(rng, -bound, bound);
    }
    for (Eigen::Index i = 0; i < out; ++i) {
      parameters_[bias_offsets_[layer] + i] =
          options.zero_bias_init ? 0.0 : uniform(rng, -bound, bound);
    }
  }
}

void Mlp::set_parameters(const Eigen::Ref<const Eigen::VectorXd>& parameters) {
  if (parameters.size() != parameters_.size()) {
    throw std::invalid_argument("Mlp::set_parameters: parameters has " +
                                std::to_string(parameters.size()) + " entries, the network " +
                                sizes_to_string(layer_sizes_) + " has " +
                                std::to_string(parameters_.size()));
  }
  parameters_ = parameters;
}

Eigen::Map<const RowMajorMatrixXd> Mlp::weights(int layer) const {
  return Eigen::Map<const RowMajorMatrixXd>(parameters_.data() + weight_offsets_.at(layer),
                                            layer_sizes_.at(layer + 1), layer_sizes_.at(layer));
}

Eigen::Map<const Eigen::VectorXd> Mlp::bias(int layer) const {
  return Eigen::Map<const Eigen::VectorXd>(parameters_.data() + bias_offsets_.at(layer),
                                           layer_sizes_.at(layer + 1));
}

void Mlp::forward(const Eigen::Ref<const Eigen::VectorXd>& input,
                  Eigen::Ref<Eigen::VectorXd> output, MlpSampleWorkspace& workspace) const {
  if (input.size() != input_size()) {
    throw std::invalid_argument("Mlp::forward: input has " + std::to_string(input.size()) +
                                " entries, expected " + std::to_string(input_size()));
  }
  if (output.size() != output_size()) {
    throw std::invalid_argument("Mlp::forward: output has " + std::to_string(output.size()) +
                                " entries, expected " + std::to_string(output_size()));
  }
  auto& outputs = workspace.layer_outputs;
  if (outputs.size() != static_cast<std::size_t>(num_layers())) outputs.resize(num_layers());
  for (int layer = 0; layer < num_layers(); ++layer) {
    Eigen::VectorXd& z = outputs[layer];
    if (z.size() != layer_sizes_[layer + 1]) z.resize(layer_sizes_[layer + 1]);
    if (layer == 0) {
      z.noalias() = weights(layer) * input;  // z = W x + b
    } else {
      z.noalias() = weights(layer) * outputs[layer - 1];
    }
    z += bias(layer);
    if (layer + 1 < num_layers()) activate_in_place(z, activation_);
  }
  output = outputs.back();
}

Eigen::VectorXd Mlp::forward(const Eigen::Ref<const Eigen::VectorXd>& input) const {
  MlpSampleWorkspace workspace;
  Eigen::VectorXd output(output_size());
  forward(input, output, workspace);
  return output;
}

const Eigen::MatrixXd& Mlp::forward_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                                          MlpBatchWorkspace& workspace) const {
  if (inputs.cols() != input_size()) {
    throw std::invalid_argument("Mlp::forward_batch: inputs have " +
                                std::to_string(inputs.cols()) + " columns, expected " +
                                std::to_string(input_size()) + " (one sample per row)");
  }
  if (dtype_ == Dtype::float32) {
    cached_forward<float>(*this, inputs, workspace);
  } else {
    cached_forward<double>(*this, inputs, workspace);
  }
  workspace.cached_rows = inputs.rows();
  workspace.cached_dtype = dtype_;
  return workspace.outputs;
}

void Mlp::check_batch_workspace(const MlpBatchWorkspace& workspace, const char* where) const {
  const std::size_t layers = static_cast<std::size_t>(num_layers());
  const bool sized = workspace.cached_dtype == Dtype::float32
                         ? workspace.f32.layer_outputs.size() == layers && workspace.f32.input.cols() == input_size()
                         : workspace.f64.layer_outputs.size() == layers && workspace.f64.input.cols() == input_size();
  if (workspace.cached_rows < 0 || workspace.cached_dtype != dtype_ || !sized) {
    throw std::logic_error(std::string(where) +
                           ": workspace holds no forward pass of this network (call forward_batch first)");
  }
}

void Mlp::backward_batch(const Eigen::Ref<const Eigen::MatrixXd>& output_gradients,
                         MlpBatchWorkspace& workspace,
                         Eigen::Ref<Eigen::VectorXd> parameter_gradient) const {
  check_batch_workspace(workspace, "Mlp::backward_batch");
  const Eigen::Index rows = workspace.rows();
  if (output_gradients.rows() != rows || output_gradients.cols() != output_size()) {
    throw std::invalid_argument(
        "Mlp::backward_batch: output_gradients is " + std::to_string(output_gradients.rows()) +
        " x " + std::to_string(output_gradients.cols()) + ", expected " + std::to_string(rows) +
        " x " + std::to_string(output_size()) + " (the last forward batch)");
  }
  check_parameter_vector(parameter_gradient.size(), "Mlp::backward_batch: parameter_gradient");
  if (dtype_ == Dtype::float32) {
    cached_backward<float>(*this, output_gradients, workspace, parameter_gradient);
  } else {
    cached_backward<double>(*this, output_gradients, workspace, parameter_gradient);
  }
}

void Mlp::input_gradient_batch(const Eigen::Ref<const Eigen::MatrixXd>& output_gradients,
                               MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::MatrixXd> input_gradient) const {
  check_batch_workspace(workspace, "Mlp::input_gradient_batch");
  const Eigen::Index rows = workspace.rows();
  if (output_gradients.rows() != rows || output_gradients.cols() != output_size() ||
      input_gradient.rows() != rows || input_gradient.cols() != input_size()) {
    throw std::invalid_argument("Mlp::input_gradient_batch: output_gradients is " +
                                std::to_string(output_gradients.rows()) + " x " +
                                std::to_string(output_gradients.cols()) + " and input_gradient " +
                                std::to_string(input_gradient.rows()) + " x " + std::to_string(input_gradient.cols()) +
                                ", expected " + std::to_string(rows) + " x " + std::to_string(output_size()) +
                                " and " + std::to_string(rows) + " x " + std::to_string(input_size()));
  }
  if (dtype_ == Dtype::float32) {
    cached_input_gradient<float>(*this, output_gradients, workspace, input_gradient);
  } else {
    cached_input_gradient<double>(*this, output_gradients, workspace, input_gradient);
  }
}

const Eigen::MatrixXd& Mlp::jvp_batch(const Eigen::Ref<const Eigen::VectorXd>& direction,
                                      MlpBatchWorkspace& workspace) const {
  check_batch_workspace(workspace, "Mlp::jvp_batch");
  check_parameter_vector(direction.size(), "Mlp::jvp_batch: direction");
  if (dtype_ == Dtype::float32) {
    cached_jvp<float>(*this, direction, workspace);
  } else {
    cached_jvp<double>(*this, direction, workspace);
  }
  return workspace.tangents;
}

void Mlp::gauss_newton_product(const Eigen::Ref<const Eigen::VectorXd>& direction, double scale,
                               MlpBatchWorkspace& workspace, Eigen::Ref<Eigen::VectorXd> product) const {
  check_batch_workspace(workspace, "Mlp::gauss_newton_product");
  check_parameter_vector(direction.size(), "Mlp::gauss_newton_product: direction");
  check_parameter_vector(product.size(), "Mlp::gauss_newton_product: product");
  if (dtype_ == Dtype::float32) {
    cached_gauss_newton<float>(*this, direction, scale, workspace, product);
  } else {
    cached_gauss_newton<double>(*this, direction, scale, workspace, product);
  }
}

void Mlp::evaluate_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs, Eigen::Ref<Eigen::MatrixXd> outputs,
                         MlpBatchWorkspace& workspace) const {
  if (inputs.cols() != input_size() || outputs.rows() != inputs.rows() || outputs.cols() != output_size()) {
    throw std::invalid_argument("Mlp::evaluate_batch: inputs " + std::to_string(inputs.rows()) + " x " +
                                std::to_string(inputs.cols()) + " and outputs " + std::to_string(outputs.rows()) +
                                " x " + std::to_string(outputs.cols()) + " do not match N x " +
                                std::to_string(input_size()) + " and N x " + std::to_string(output_size()));
  }
  if (dtype_ == Dtype::float32) {
    streamed_evaluate<float>(*this, inputs, outputs, workspace);
  } else {
    streamed_evaluate<double>(*this, inputs, outputs, workspace);
  }
}

void Mlp::gradient_batch(const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                         const OutputGradientFunction& output_gradient, MlpBatchWorkspace& workspace,
                         Eigen::Ref<Eigen::VectorXd> parameter_gradient) const {
  if (inputs.cols() != input_size()) {
    throw std::invalid_argument("Mlp::gradient_batch: inputs have " + std::to_string(inputs.cols()) +
                                " columns, expected " + std::to_string(input_size()) + " (one sample per row)");
  }
  check_parameter_vector(parameter_gradient.size(), "Mlp::gradient_batch: parameter_gradient");
  if (dtype_ == Dtype::float32) {
    streamed_gradient<float>(*this, inputs, output_gradient, workspace, parameter_gradient);
  } else {
    streamed_gradient<double>(*this, inputs, output_gradient, workspace, parameter_gradient);
  }
}

void Mlp::check_parameter_vector(Eigen::Index size, const char* what) const {
  if (size != num_parameters()) {
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(size) + " entries, expected " +
                                std::to_string(num_parameters()));
  }
}

}  // namespace bsg
