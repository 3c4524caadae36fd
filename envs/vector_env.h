// N environments of one id stepped together on a pool of threads (the shape of
// EnvPool): the caller hands in one action row per environment, every
// environment steps on some worker thread, and the results land in batched
// buffers the VectorEnv owns. An environment that ends its episode (terminated
// or truncated) is reset at once, so the batch always holds live episodes; the
// observation the step itself produced is kept as its final observation.
//
// Parameters:
//   id           a registered environment id (env.h make())
//   num_envs     N >= 1
//   num_threads  worker threads including the caller; 0 (default): the
//                machine's hardware threads, at most N
//   options      EnvOptions passed to every environment (default: defaults)
//
// Seeding: reset(seed) resets environment i with seed + i (gymnasium's and
// EnvPool's convention), so environment i of a new VectorEnv plays exactly
// what a new single Env reset with seed + i plays under the same actions. (A
// reset is not a pure function of its seed: later resets restore the first
// reset's snapshot and motor targets survive them, as in the original suite.) Auto-resets
// continue each environment's own random stream (Env::reset()). Each
// environment is touched by one thread at a time and environments share
// nothing, so results are bit-identical whatever num_threads is.
//
// Threading: the VectorEnv itself is not thread-safe; call it from one thread.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/env.h"

namespace bsg::envs {

class VectorEnvWorkers;

class VectorEnv {
 public:
  // Throws std::invalid_argument for an unknown id (listing the ids),
  // num_envs < 1 or num_threads < 0.
  VectorEnv(const std::string& id, int num_envs, int num_threads = 0,
            const EnvOptions& options = {});
  // The same for any description (env_description.h), checked before the first build.
  VectorEnv(const EnvDescription& description, int num_envs, int num_threads = 0,
            const EnvOptions& options = {});
  ~VectorEnv();
  VectorEnv(const VectorEnv&) = delete;
  VectorEnv& operator=(const VectorEnv&) = delete;

  const EnvSpec& spec() const { return spec_; }
  int num_envs() const { return num_envs_; }
  int num_threads() const { return num_threads_; }
  // Names of the cost terms, in the column order of cost_terms(); known from
  // the first step on (empty before).
  const std::vector<std::string>& cost_term_names() const { return cost_term_names_; }

  // Resets environment i with seed + i; observations() then holds the
  // first observations.
  void reset(std::uint64_t seed);
  // Resets every environment, continuing its random stream.
  void reset();

  // Steps every environment with its row of `actions` (N x action_dim,
  // row-major). Throws std::invalid_argument if the size is not
  // N * action_dim or an entry is not finite (nothing is stepped then), and
  // std::logic_error before the first reset.
  void step(std::span<const double> actions);

  // Buffers of the last reset()/step(), valid until the next call.
  std::span<const double> observations() const { return observations_; }        // N x obs_dim
  std::span<const double> final_observations() const { return final_observations_; }  // N x obs_dim
  std::span<const double> rewards() const { return rewards_; }
  std::span<const double> costs() const { return costs_; }
  std::span<const std::uint8_t> terminated() const { return terminated_; }
  std::span<const std::uint8_t> truncated() const { return truncated_; }
  std::span<const double> cost_terms() const { return cost_terms_; }  // N x cost_term_names().size()

 private:
  void check_actions(std::span<const double> actions) const;
  void reset_one(int index, const std::uint64_t* seed);
  void step_one(int index, std::span<const double> actions);

  std::vector<std::unique_ptr<Env>> envs_;
  EnvSpec spec_;
  int num_envs_;
  int num_threads_;
  std::vector<std::string> cost_term_names_;
  bool has_reset_ = false;

  std::vector<double> observations_;
  std::vector<double> final_observations_;
  std::vector<double> rewards_;
  std::vector<double> costs_;
  std::vector<std::uint8_t> terminated_;
  std::vector<std::uint8_t> truncated_;
  std::vector<double> cost_terms_;
  std::vector<std::vector<double>> env_cost_terms_;  // per environment, filled by its thread

  std::unique_ptr<VectorEnvWorkers> workers_;
};

}  // namespace bsg::envs
