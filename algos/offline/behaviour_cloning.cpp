#include "algos/offline/behaviour_cloning.h"

#include <cmath>
#include <stdexcept>

#include "common/adam.h"
#include "common/random.h"

namespace bsg::algos {

ClonedPolicy::ClonedPolicy(Mlp network, Eigen::VectorXd observation_mean, Eigen::VectorXd observation_std,
                           std::string name)
    : network_(std::move(network)),
      mean_(std::move(observation_mean)),
      std_(std::move(observation_std)),
      name_(std::move(name)),
      input_(network_.input_size()),
      output_(network_.output_size()) {}

void ClonedPolicy::act(std::span<const double> observation, std::span<double> action) {
  if (static_cast<int>(observation.size()) != network_.input_size() ||
      static_cast<int>(action.size()) != network_.output_size()) {
    throw std::invalid_argument(name_ + ": takes " + std::to_string(network_.input_size()) + " observations and gives " +
                                std::to_string(network_.output_size()) + " actions, the environment has " +
                                std::to_string(observation.size()) + " and " + std::to_string(action.size()));
  }
  input_ = (Eigen::Map<const Eigen::VectorXd>(observation.data(), input_.size()) - mean_).cwiseQuotient(std_);
  network_.forward(input_, output_, workspace_);
  Eigen::Map<Eigen::VectorXd>(action.data(), output_.size()) = output_;
}

Eigen::VectorXd ClonedPolicy::action(const Eigen::Ref<const Eigen::VectorXd>& observation) const {
  return network_.forward((observation - mean_).cwiseQuotient(std_));
}

BehaviourCloningResult train_behaviour_cloning(const OfflineDataset& dataset, const BehaviourCloningOptions& options) {
  if (options.updates < 1 || options.batch_size < 1 || !(options.learning_rate > 0.0) ||
      !std::isfinite(options.learning_rate)) {
    throw std::invalid_argument("behaviour cloning: updates and batch size must be >= 1 and the learning rate positive");
  }
  for (int size : options.hidden_sizes) {
    if (size < 1) throw std::invalid_argument("behaviour cloning: a hidden layer must have at least 1 unit");
  }
  check_dataset_shapes(dataset);
  // The training rows.
  std::vector<std::size_t> rows;
  std::size_t episodes = 0;
  if (options.safe_only) {
    for (const DatasetEpisode& e : dataset_episodes(dataset)) {
      if (e.cost_return > options.cost_limit) continue;
      ++episodes;
      for (std::size_t t = e.begin; t < e.end; ++t) rows.push_back(t);
    }
    if (rows.empty()) {
      throw std::invalid_argument("behaviour cloning: BC-Safe finds no episode with cost return <= " +
                                  std::to_string(options.cost_limit) + " in the dataset");
    }
  } else {
    episodes = dataset_episodes(dataset).size();
    for (std::size_t t = 0; t < dataset.size(); ++t) rows.push_back(t);
    if (rows.empty()) throw std::invalid_argument("behaviour cloning: the dataset is empty");
  }
  const int obs = dataset.observation_dim;
  const int act = dataset.action_dim;
  const auto observation = [&](std::size_t row) {
    return Eigen::Map<const Eigen::VectorXf>(dataset.observations.data() + row * static_cast<std::size_t>(obs), obs)
        .cast<double>();
  };
  // Standardisation constants of the training rows; a constant input keeps scale 1.
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(obs);
  for (std::size_t row : rows) mean += observation(row);
  mean /= static_cast<double>(rows.size());
  Eigen::VectorXd variance = Eigen::VectorXd::Zero(obs);
  for (std::size_t row : rows) variance += (observation(row) - mean).array().square().matrix();
  variance /= static_cast<double>(rows.size());
  Eigen::VectorXd std = variance.cwiseSqrt();
  for (Eigen::Index k = 0; k < obs; ++k) {
    if (!(std[k] > 1e-8)) std[k] = 1.0;
  }

  std::vector<int> layers{obs};
  layers.insert(layers.end(), options.hidden_sizes.begin(), options.hidden_sizes.end());
  layers.push_back(act);
  Rng rng(options.seed);
  Mlp network(layers, rng);
  Adam adam(network.num_parameters(), {.learning_rate = options.learning_rate});
  MlpBatchWorkspace workspace;
  const Eigen::Index batch = options.batch_size;
  Eigen::MatrixXd inputs(batch, obs);
  Eigen::MatrixXd targets(batch, act);
  Eigen::MatrixXd output_gradients(batch, act);
  Eigen::VectorXd gradient(network.num_parameters());
  double loss = 0.0;
  for (int update = 0; update < options.updates; ++update) {
    for (Eigen::Index i = 0; i < batch; ++i) {
      const std::size_t row = rows[uniform_index(rng, rows.size())];
      inputs.row(i) = (observation(row) - mean).cwiseQuotient(std).transpose();
      targets.row(i) = Eigen::Map<const Eigen::VectorXf>(dataset.actions.data() + row * static_cast<std::size_t>(act), act)
                           .cast<double>()
                           .transpose();
    }
    const Eigen::MatrixXd& outputs = network.forward_batch(inputs, workspace);
    const Eigen::MatrixXd error = outputs - targets;
    const double elements = static_cast<double>(batch * act);
    loss = error.squaredNorm() / elements;  // torch's mse_loss: the mean over every element
    output_gradients = (2.0 / elements) * error;
    network.backward_batch(output_gradients, workspace, gradient);
    adam.step(network.mutable_parameters(), gradient);
  }
  BehaviourCloningResult result;
  result.policy = std::make_unique<ClonedPolicy>(std::move(network), mean, std,
                                                 options.safe_only ? "BC-Safe" : "BC-All");
  result.rows = rows.size();
  result.episodes = episodes;
  result.final_loss = loss;
  return result;
}

}  // namespace bsg::algos
