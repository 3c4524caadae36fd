// Behaviour cloning, the simplest offline baselines of OSRL (docs/datasets.md#behaviour-cloning):
// a deterministic policy a = f(s_hat), an MLP (common/mlp.h, tanh hidden
// layers, linear output) on observations standardised with the training
// rows' mean and standard deviation, fitted by Adam (common/adam.h) to the
// dataset's actions with the mean squared error over minibatches drawn
// uniformly with replacement.
//   BC-All:  every row of the dataset;
//   BC-Safe: only the rows of complete episodes whose cost return is at most
//            the cost limit (OSRL's BC-Safe).
//
// Parameters (BehaviourCloningOptions, defaults as OSRL's BC where it has one):
//   safe_only       false (BC-All)
//   cost_limit      0; BC-Safe keeps episodes with cost return <= cost_limit
//   hidden_sizes    {256, 256}; empty: a linear policy
//   updates         20000 Adam steps
//   batch_size      512
//   learning_rate   1e-3
//   seed            0: network initialisation and minibatch draws
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "algos/offline/collection_policy.h"
#include "algos/offline/offline_dataset.h"
#include "common/mlp.h"

namespace bsg::algos {

struct BehaviourCloningOptions {
  bool safe_only = false;
  double cost_limit = 0.0;
  std::vector<int> hidden_sizes{256, 256};
  int updates = 20000;
  int batch_size = 512;
  double learning_rate = 1e-3;
  std::uint64_t seed = 0;
};

// The cloned policy, usable as a collection policy (its episodes are then an
// evaluation): deterministic, so start_episode does nothing.
class ClonedPolicy final : public CollectionPolicy {
 public:
  ClonedPolicy(Mlp network, Eigen::VectorXd observation_mean, Eigen::VectorXd observation_std, std::string name);
  std::string description() const override { return name_; }
  void start_episode(std::uint64_t) override {}
  void act(std::span<const double> observation, std::span<double> action) override;
  // The action for one observation (allocates; for tests).
  Eigen::VectorXd action(const Eigen::Ref<const Eigen::VectorXd>& observation) const;
  const Mlp& network() const { return network_; }

 private:
  Mlp network_;
  Eigen::VectorXd mean_;
  Eigen::VectorXd std_;
  std::string name_;
  Eigen::VectorXd input_;
  Eigen::VectorXd output_;
  MlpSampleWorkspace workspace_;
};

struct BehaviourCloningResult {
  std::unique_ptr<ClonedPolicy> policy;
  std::size_t rows = 0;      // training rows
  std::size_t episodes = 0;  // complete episodes among them (BC-Safe: those kept)
  double final_loss = 0.0;   // mean squared error of the last minibatch
};

// Throws std::invalid_argument with one line if the options are out of range
// or BC-Safe finds no episode within the cost limit.
BehaviourCloningResult train_behaviour_cloning(const OfflineDataset& dataset, const BehaviourCloningOptions& options);

}  // namespace bsg::algos
