// Speed of the learning core's hot paths (printed, never asserted):
// one-observation policy forward, batch forward of 1000, backward over 32000
// samples, and one Fisher-vector product over 8000 sub-sampled rows (a local
// batch of 32000, every 4th row), for a small and a large problem size, in
// both dtypes of the batch passes (the one-observation passes are always double).
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "algos/trust_region/fisher_vector_product.h"
#include "algos/core/gaussian_policy.h"
#include "common/mlp.h"
#include "common/mpi_context.h"
#include "common/random.h"

namespace {

using Clock = std::chrono::steady_clock;

// Mean wall time of one call in microseconds, over enough repetitions to fill ~0.5 s.
double time_us(const std::function<void()>& call, double budget_seconds = 0.5) {
  call();  // warm-up (sizes workspaces)
  long repetitions = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    for (int i = 0; i < 8; ++i) call();
    repetitions += 8;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < budget_seconds);
  return 1e6 * elapsed / static_cast<double>(repetitions);
}

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, bsg::Rng& rng) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = bsg::standard_normal(rng);
  return m;
}

volatile double sink = 0.0;  // keeps results alive

void run_case(int observation_size, int action_size, bsg::Dtype dtype) {
  bsg::Rng rng(0);
  bsg::algos::GaussianPolicy policy(observation_size, action_size, {64, 64}, rng, bsg::MlpOptions{false, dtype});
  const bsg::Mlp& net = policy.mean_net();

  const Eigen::VectorXd observation = random_matrix(observation_size, 1, rng);
  Eigen::VectorXd action(action_size);
  bsg::MlpSampleWorkspace sample_workspace;
  const double forward_one = time_us([&] {
    policy.mean_action(observation, action, sample_workspace);
    sink = sink + action[0];
  });
  bsg::Rng noise(1);
  const double sample_one = time_us([&] {
    sink = sink + policy.sample_action(observation, action, noise, sample_workspace);
  });

  const Eigen::MatrixXd batch_1000 = random_matrix(1000, observation_size, rng);
  bsg::MlpBatchWorkspace workspace_1000;
  const double forward_1000 = time_us([&] { sink = sink + net.forward_batch(batch_1000, workspace_1000)(0, 0); });

  const Eigen::MatrixXd batch_32000 = random_matrix(32000, observation_size, rng);
  const Eigen::MatrixXd output_gradients = random_matrix(32000, action_size, rng);
  bsg::MlpBatchWorkspace workspace_32000;
  Eigen::VectorXd gradient(net.num_parameters());
  const double forward_32000 = time_us([&] { sink = sink + net.forward_batch(batch_32000, workspace_32000)(0, 0); });
  net.forward_batch(batch_32000, workspace_32000);
  const double backward_32000 = time_us([&] {
    net.backward_batch(output_gradients, workspace_32000, gradient);
    sink = sink + gradient[0];
  });

  bsg::algos::FisherVectorProduct fvp(policy, batch_32000, bsg::MpiContext::single_process());
  const Eigen::VectorXd direction = random_matrix(net.num_parameters(), 1, rng);
  Eigen::VectorXd product(net.num_parameters());
  const double fvp_8000 = time_us([&] {
    fvp.apply(direction, product);
    sink = sink + product[0];
  });

  std::printf("| %7s | %3d | %3d | %6ld | %9.2f | %8.2f | %8.0f | %9.0f | %9.0f | %8.0f |\n", std::string(bsg::to_string(dtype)).c_str(),
              observation_size, action_size, static_cast<long>(net.num_parameters()), forward_one, sample_one, forward_1000, forward_32000,
              backward_32000, fvp_8000);
}

}  // namespace

int main() {
  std::printf("bsg core benchmark (64-64 tanh policy, one thread); times in microseconds\n\n");
  std::printf("| dtype   | d_o | d_a | params | fwd 1 obs | sample 1 | fwd 1000 | fwd 32000 | bwd 32000 | FVP 8000 |\n");
  std::printf("|---------|----:|----:|-------:|----------:|---------:|---------:|----------:|----------:|---------:|\n");
  for (const bsg::Dtype dtype : {bsg::Dtype::float64, bsg::Dtype::float32}) {
    run_case(8, 2, dtype);
    run_case(83, 8, dtype);
  }
  std::printf("\nFVP 8000 = one Fisher-vector product over the 8000 rows sub-sampled from a 32000-row batch\n"
              "(JVP + VJP + damping; no MPI). bwd 32000 = parameter gradient after a cached forward pass.\n");
  return sink == 12345.678 ? 1 : 0;
}
