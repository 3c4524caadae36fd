// Behaviour cloning, the simplest offline baselines of OSRL (docs/datasets.md#behaviour-cloning),
// as an offline algorithm (BehaviourCloning, trained in runs of `alg: bc-all | bc-safe`) and as
// train_behaviour_cloning (`bsg dataset bc`), which takes the same steps:
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
#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "algos/offline/offline_dataset.h"
#include "common/adam.h"
#include "common/mlp.h"

namespace bsg::algos {

// BC-All and BC-Safe as an offline algorithm (offline_algorithm.h): they differ only in their
// training rows (offline_batches.h: all_rows, rows_within_cost_limit). One step on a batch of
// standardised observations S and actions A: L = mean over every element of (f(S) - A)^2 (torch's
// mse_loss), dL/df = 2 (f(S) - A) / (batch * |A|), then Adam. It acts with a = f((s - mean) / std),
// the same action in both modes.
class BehaviourCloning final : public OfflineAlgorithm {
 public:
  // The network obs -> hidden_sizes -> act drawn from `init_rng` (common/mlp.h).
  BehaviourCloning(std::string name, int observation_size, int action_size, ObservationScaling scaling,
                   const std::vector<int>& hidden_sizes, MlpOptions network_options, double learning_rate,
                   Rng& init_rng);
  BehaviourCloning(const BehaviourCloning&) = delete;  // its acting policy refers to it
  BehaviourCloning& operator=(const BehaviourCloning&) = delete;

  std::string_view name() const override { return name_; }
  double update(const OfflineBatch& batch, Rng& noise) override;  // draws nothing
  ActingPolicy& acting() override { return acting_; }
  void save(BinaryWriter& writer) const override;
  void load(BinaryReader& reader) override;

  const Mlp& network() const { return network_; }
  const ObservationScaling& scaling() const override { return scaling_; }

 private:
  class Acting final : public ActingPolicy {
   public:
    explicit Acting(const BehaviourCloning& owner);
    int observation_size() const override { return owner_.network_.input_size(); }
    int action_size() const override { return owner_.network_.output_size(); }
    void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override;

   private:
    const BehaviourCloning& owner_;
    Eigen::VectorXd input_;
    Eigen::VectorXd output_;
    MlpSampleWorkspace workspace_;
  };

  std::string name_;
  ObservationScaling scaling_;
  Mlp network_;
  Adam adam_;
  MlpBatchWorkspace workspace_;
  Eigen::MatrixXd output_gradients_;
  Eigen::VectorXd gradient_;
  Acting acting_;
};

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
