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
// Gymnasium 1.x (docs/python.md#vector-environments) adds three things, each off by default so
// that the C++ behaviour above is unchanged:
//   set_autoreset(kNextStep)   an ended environment keeps its final observation and is reset
//                              by the next step() instead of being stepped (reward 0, flags
//                              false); autoreset_envs() tells which ones were;
//   set_max_episode_steps(L)   truncation after L steps instead of the environment's own length;
//   reset_selected(mask, seeds) resets some environments, each with its own seed or none; a
//                              seeded one is rebuilt first, so that its episode is a pure
//                              function of the seed whatever it played before.
//
// Threading: the VectorEnv itself is not thread-safe; call it from one thread.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "envs/env.h"

namespace bsg::envs {

class WorkerPool;

// When step() resets an environment whose episode ended (Gymnasium's AutoresetMode).
enum class AutoReset {
  kSameStep,  // in the step that ended it (the default): observations() holds the new episode
  kNextStep,  // in the following step, which resets it instead of stepping it
};

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
  // Resets environment i if mask[i] != 0 (every one if mask is empty): with
  // seeds[i] after rebuilding it from scratch (the same episode as a new
  // environment reset with that seed), or continuing its stream if seeds[i] is
  // empty. Rows of the others keep their observations. Throws
  // std::invalid_argument if a non-empty mask or seeds has not N entries.
  void reset_selected(std::span<const std::uint8_t> mask,
                      std::span<const std::optional<std::uint64_t>> seeds);

  void set_autoreset(AutoReset mode) { autoreset_ = mode; }
  AutoReset autoreset() const { return autoreset_; }
  // Episode length: 0 (default) keeps the environment's own truncation; L >= 1
  // truncates after L steps instead (throws std::invalid_argument if < 0).
  void set_max_episode_steps(int steps);
  int max_episode_steps() const {
    return max_episode_steps_ > 0 ? max_episode_steps_ : spec_.max_episode_steps;
  }

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
  // kNextStep: the environments the last step() reset instead of stepping.
  std::span<const std::uint8_t> autoreset_envs() const { return autoreset_envs_; }

  // Runs job(i, environment i) for every environment on the pool's threads,
  // each environment on one thread at a time (rendering them all: render/);
  // rethrows the first exception a job threw. Not on the step path.
  void for_each_env(const std::function<void(int, const Env&)>& job);

 private:
  void check_actions(std::span<const double> actions) const;
  void reset_one(int index, const std::uint64_t* seed);
  void step_one(int index, std::span<const double> actions);
  void autoreset_one(int index);  // kNextStep: the reset that replaces a step

  std::function<std::unique_ptr<Env>()> make_env_;  // builds one new environment
  std::vector<std::unique_ptr<Env>> envs_;
  EnvSpec spec_;
  int num_envs_;
  int num_threads_;
  std::vector<std::string> cost_term_names_;
  bool has_reset_ = false;
  AutoReset autoreset_ = AutoReset::kSameStep;
  int max_episode_steps_ = 0;
  std::vector<int> elapsed_steps_;           // per environment, for max_episode_steps_
  std::vector<std::uint8_t> ended_;          // kNextStep: to be reset by the next step
  std::vector<std::uint8_t> autoreset_envs_;
  std::vector<std::uint8_t> used_;           // reset since built: reset_selected() rebuilds it

  std::vector<double> observations_;
  std::vector<double> final_observations_;
  std::vector<double> rewards_;
  std::vector<double> costs_;
  std::vector<std::uint8_t> terminated_;
  std::vector<std::uint8_t> truncated_;
  std::vector<double> cost_terms_;
  std::vector<std::vector<double>> env_cost_terms_;  // per environment, filled by its thread

  std::unique_ptr<WorkerPool> workers_;  // envs/worker_pool.h
};

}  // namespace bsg::envs
