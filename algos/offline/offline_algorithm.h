// The offline algorithms (design.md "Off-policy and offline learning"; docs/architecture.md
// "Adding an offline algorithm"): a gradient step on a batch drawn from a fixed dataset, an acting
// policy for the online evaluations, and a state for the checkpoint. The offline family
// (algos/training/offline_family.h) draws the batches (offline_batches.h), counts the epochs,
// evaluates and saves; an algorithm never touches an environment.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algos/core/acting_policy.h"
#include "algos/core/algorithm.h"
#include "common/binary_io.h"
#include "common/random.h"

namespace bsg::algos {

struct ObservationScaling;  // offline_batches.h

// One minibatch, row i a transition of the dataset: the observations standardised with the training
// rows' mean and standard deviation (offline_batches.h), the rest as the dataset holds it.
struct OfflineBatch {
  Eigen::MatrixXd observations;       // batch x observation size, standardised
  Eigen::MatrixXd actions;            // batch x action size
  Eigen::MatrixXd next_observations;  // batch x observation size, standardised as the observations
  Eigen::VectorXd rewards;            // batch
  Eigen::VectorXd costs;              // batch (the dataset's costs: with several constraints their sum)
  Eigen::VectorXd terminals;          // batch, 1 where the environment ended the episode (no bootstrap)
  Eigen::VectorXd initial;            // batch, 1 for an episode's first row (OSRL's is_init; COptiDICE)
};

class OfflineAlgorithm {
 public:
  virtual ~OfflineAlgorithm() = default;
  // "BC-All", "BC-Safe", "CPQ", "BCQ-Lag", "COptiDICE".
  virtual std::string_view name() const = 0;
  // One gradient step on `batch`, drawing any noise it needs (sampled actions, a VAE's latent) from
  // `noise`, the family's batch stream; returns its loss (the batch's, before the step).
  virtual double update(const OfflineBatch& batch, Rng& noise) = 0;
  // The policy as it acts now (on raw observations; its standardisation inside).
  virtual ActingPolicy& acting() = 0;
  // The training rows' observation mean and standard deviation: the policy acts on
  // (s - mean) / std, as the batches hold it; a loader that reports the policy's input says it.
  virtual const ObservationScaling& scaling() const = 0;
  // The learner's whole state (networks, optimisers, standardisation), for the checkpoint; load
  // fails on the reader naming the field if the sizes are not this algorithm's.
  virtual void save(BinaryWriter& writer) const = 0;
  virtual void load(BinaryReader& reader) = 0;
};

}  // namespace bsg::algos
