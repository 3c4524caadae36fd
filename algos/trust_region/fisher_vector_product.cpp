#include "algos/trust_region/fisher_vector_product.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

FisherVectorProduct::FisherVectorProduct(const GaussianPolicy& policy,
                                         const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                         const MpiContext& mpi, FisherVectorProductOptions options)
    : mean_net_(policy.mean_net()), std_(policy.std()), mpi_(mpi), options_(options) {
  if (options.subsample_stride <= 0) {
    throw std::invalid_argument("FisherVectorProduct: subsample_stride must be positive, got " +
                                std::to_string(options.subsample_stride));
  }
  if (!(options.damping_coeff >= 0.0)) {
    throw std::invalid_argument("FisherVectorProduct: damping_coeff must be >= 0, got " +
                                std::to_string(options.damping_coeff));
  }
  if (observations.cols() != policy.observation_size()) {
    throw std::invalid_argument("FisherVectorProduct: observations have " + std::to_string(observations.cols()) +
                                " columns, the policy expects " + std::to_string(policy.observation_size()));
  }
  if (observations.rows() == 0) throw std::invalid_argument("FisherVectorProduct: observations are empty");
  const Eigen::Index stride = options.subsample_stride;
  const Eigen::Index rows = (observations.rows() + stride - 1) / stride;  // N_f = ceil(N / 4)
  subsampled_observations_.resize(rows, observations.cols());
  for (Eigen::Index i = 0; i < rows; ++i) subsampled_observations_.row(i) = observations.row(i * stride);
  mean_net_.forward_batch(subsampled_observations_, workspace_);
}

void FisherVectorProduct::apply(const Eigen::Ref<const Eigen::VectorXd>& direction,
                                Eigen::Ref<Eigen::VectorXd> product) {
  if (direction.size() != num_parameters()) {
    throw std::invalid_argument("FisherVectorProduct::apply: direction has " + std::to_string(direction.size()) +
                                " entries, the policy has " + std::to_string(num_parameters()) + " parameters");
  }
  if (product.size() != num_parameters()) {
    throw std::invalid_argument("FisherVectorProduct::apply: product has " + std::to_string(product.size()) +
                                " entries, the policy has " + std::to_string(num_parameters()) + " parameters");
  }
  if (direction.data() == product.data()) {
    throw std::invalid_argument("FisherVectorProduct::apply: product must not alias direction");
  }
  ++call_count_;
  // 1/(N_f d_a sigma^2) sum_i J_i^T (J_i v)
  const double scale =
      1.0 / (static_cast<double>(num_samples() * mean_net_.output_size()) * std_ * std_);
  mean_net_.gauss_newton_product(direction, scale, workspace_, product);
  mpi_.average_in_place(product);             // avg over ranks, then
  product += options_.damping_coeff * direction;  // + damping v
}

}  // namespace bsg::algos
