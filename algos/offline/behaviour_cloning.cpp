#include "algos/offline/behaviour_cloning.h"

#include <cmath>
#include <stdexcept>

#include "algos/core/adam_state.h"
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

BehaviourCloning::BehaviourCloning(std::string name, int observation_size, int action_size, ObservationScaling scaling,
                                   const std::vector<int>& hidden_sizes, MlpOptions network_options,
                                   double learning_rate, Rng& init_rng)
    : name_(std::move(name)),
      scaling_(std::move(scaling)),
      network_(
          [&] {
            std::vector<int> layers{observation_size};
            layers.insert(layers.end(), hidden_sizes.begin(), hidden_sizes.end());
            layers.push_back(action_size);
            return layers;
          }(),
          init_rng, network_options),
      adam_(network_.num_parameters(), {.learning_rate = learning_rate}),
      gradient_(network_.num_parameters()),
      acting_(*this) {
  if (scaling_.mean.size() != observation_size || scaling_.std.size() != observation_size) {
    throw std::invalid_argument(name_ + ": the observation scaling has " + std::to_string(scaling_.mean.size()) +
                                " features, the observations " + std::to_string(observation_size));
  }
}

double BehaviourCloning::update(const OfflineBatch& batch, Rng& /*draws nothing*/) {
  if (batch.observations.cols() != network_.input_size() || batch.actions.cols() != network_.output_size() ||
      batch.observations.rows() != batch.actions.rows() || batch.observations.rows() < 1) {
    throw std::invalid_argument(name_ + ": a batch of " + std::to_string(batch.observations.rows()) + " x " +
                                std::to_string(batch.observations.cols()) + " observations and " +
                                std::to_string(batch.actions.rows()) + " x " + std::to_string(batch.actions.cols()) +
                                " actions does not fit the network");
  }
  const Eigen::MatrixXd& outputs = network_.forward_batch(batch.observations, workspace_);
  const Eigen::MatrixXd error = outputs - batch.actions;
  const double elements = static_cast<double>(batch.actions.rows() * batch.actions.cols());
  const double loss = error.squaredNorm() / elements;  // torch's mse_loss: the mean over every element
  output_gradients_ = (2.0 / elements) * error;
  network_.backward_batch(output_gradients_, workspace_, gradient_);
  adam_.step(network_.mutable_parameters(), gradient_);
  return loss;
}

void BehaviourCloning::save(BinaryWriter& writer) const {
  writer.write_section("behaviour cloning");
  writer.write_string(name_);
  writer.write_vector(scaling_.mean);
  writer.write_vector(scaling_.std);
  writer.write_vector(network_.parameters());
  save_adam_state(adam_, writer);
}

void BehaviourCloning::load(BinaryReader& reader) {
  reader.expect_section("behaviour cloning");
  if (reader.read_string("algorithm") != name_) reader.fail("not a checkpoint of " + name_);
  Eigen::VectorXd mean = reader.read_vector("observation mean", network_.input_size());
  Eigen::VectorXd std = reader.read_vector("observation std", network_.input_size());
  const Eigen::VectorXd parameters = reader.read_vector("policy parameters", network_.num_parameters());
  load_adam_state(adam_, reader, "policy");
  scaling_.mean = std::move(mean);
  scaling_.std = std::move(std);
  network_.set_parameters(parameters);
}

BehaviourCloning::Acting::Acting(const BehaviourCloning& owner)
    : owner_(owner), input_(owner.network_.input_size()), output_(owner.network_.output_size()) {}

void BehaviourCloning::Acting::act(std::span<const double> observation, ActionMode /*the same in both modes*/,
                                   Rng& /*draws nothing*/, std::span<double> action) {
  check_acting_sizes(*this, observation, action, owner_.name_.c_str());
  input_ = (Eigen::Map<const Eigen::VectorXd>(observation.data(), input_.size()) - owner_.scaling_.mean)
               .cwiseQuotient(owner_.scaling_.std);
  owner_.network_.forward(input_, output_, workspace_);
  Eigen::Map<Eigen::VectorXd>(action.data(), output_.size()) = output_;
}

BehaviourCloningResult train_behaviour_cloning(const OfflineDataset& dataset, const BehaviourCloningOptions& options) {
  if (options.updates < 1 || options.batch_size < 1 || !(options.learning_rate > 0.0) ||
      !std::isfinite(options.learning_rate)) {
    throw std::invalid_argument("behaviour cloning: updates and batch size must be >= 1 and the learning rate positive");
  }
  for (int size : options.hidden_sizes) {
    if (size < 1) throw std::invalid_argument("behaviour cloning: a hidden layer must have at least 1 unit");
  }
  const std::string name = options.safe_only ? "BC-Safe" : "BC-All";
  const OfflineBatches batches(dataset,
                               options.safe_only ? rows_within_cost_limit(dataset, options.cost_limit) : all_rows(dataset),
                               options.batch_size);
  // One stream draws the network and then every batch.
  Rng rng(options.seed);
  BehaviourCloning learner(name, dataset.observation_dim, dataset.action_dim, batches.scaling(), options.hidden_sizes,
                           MlpOptions{}, options.learning_rate, rng);
  OfflineBatch batch;
  double loss = 0.0;
  for (int update = 0; update < options.updates; ++update) {
    batches.sample(rng, batch);
    loss = learner.update(batch, rng);
  }
  BehaviourCloningResult result;
  result.policy = std::make_unique<ClonedPolicy>(learner.network(), batches.scaling().mean, batches.scaling().std, name);
  result.rows = batches.rows().rows.size();
  result.episodes = batches.rows().episodes;
  result.final_loss = loss;
  return result;
}

}  // namespace bsg::algos
