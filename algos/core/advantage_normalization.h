// What the trainer may do to the advantages between GAE and the policy update
// (docs/algorithms.md#advantages). The original does neither (Q6).
//
//   standardize_advantages: A <- (A - mean) / (std + 1e-8), A^C_i <- A^C_i - mean_i
//                           (Q6: the original's switch, never used; OmniSafe's default);
//   center_advantages:      A <- A - mean,                  A^C_i <- A^C_i - mean_i
//                           (also Q6: the batch mean goes, the relative size of reward and cost
//                           advantages that the Lagrangian and CPO-style updates weigh stays).
//
// Means and std are pooled over ranks (collective: every rank calls them).
#pragma once

#include <Eigen/Core>

#include "common/mpi_context.h"

namespace bsg::algos {

// `reward`: the rank's reward advantages; `costs`: one column of cost advantages per constraint.
void standardize_advantages(Eigen::VectorXd& reward, Eigen::MatrixXd& costs, const MpiContext& mpi);
void center_advantages(Eigen::VectorXd& reward, Eigen::MatrixXd& costs, const MpiContext& mpi);

}  // namespace bsg::algos
