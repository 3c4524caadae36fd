// PyTorch's clip_grad_norm_ as OmniSafe applies it before an optimiser step
// (docs/algorithms.md#first-order-updates, #off-policy-learners): the gradients of
// one optimiser step, taken together as one vector, are rescaled to norm
// max_norm when their norm exceeds it. max_norm 0 leaves them alone.
#pragma once

#include <Eigen/Core>
#include <span>

namespace bsg::algos {

// The norm of the concatenated `gradients` before any rescaling.
double clip_gradient_norm(std::span<Eigen::VectorXd* const> gradients, double max_norm);
double clip_gradient_norm(Eigen::VectorXd& gradient, double max_norm);

}  // namespace bsg::algos
