#include "envs/joint_control_env.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bsg::envs {

namespace {

class JointControlEnv final : public Env {
 public:
  explicit JointControlEnv(std::unique_ptr<MultiAgentEnv> team) : team_(std::move(team)) {
    const MultiAgentSpec& team_spec = team_->spec();
    spec_.id = team_spec.id;
    spec_.agent = team_spec.agent;
    spec_.task = team_spec.task;
    for (const int dim : team_spec.observation_dims) spec_.observation_dim += dim;
    for (const int dim : team_spec.action_dims) spec_.action_dim += dim;
    spec_.max_episode_steps = team_spec.max_episode_steps;
    spec_.cost_limit = team_spec.cost_limit;
    spec_.action_low = team_spec.action_low;
    spec_.action_high = team_spec.action_high;
    spec_.observation_bound = team_spec.observation_bound;
    spec_.cost_term_names = team_spec.cost_term_names;
    observation_.resize(static_cast<std::size_t>(spec_.observation_dim));
    cost_terms_.resize(spec_.cost_term_names.size());
    for (std::size_t t = 0; t < cost_terms_.size(); ++t) cost_terms_[t].name = spec_.cost_term_names[t];
    actions_.resize(team_spec.action_dims.size());
  }

  const EnvSpec& spec() const override { return spec_; }
  std::span<const double> reset(std::uint64_t seed) override { return concatenate(team_->reset(seed)); }
  std::span<const double> reset() override { return concatenate(team_->reset()); }

  std::span<const double> reset_to(const Layout& layout) override {
    one_robot("reset_to");
    return concatenate(team_->reset_to(std::span<const Layout>(&layout, 1)));
  }

  const Layout& layout() const override {
    throw std::logic_error(spec_.id + " controlled jointly keeps no layout; reset the multi-agent environment "
                                      "(make_multi_agent) with reset_to to place its robots");
  }

  StepResult step(std::span<const double> action) override {
    if (action.size() != static_cast<std::size_t>(spec_.action_dim)) {
      throw std::invalid_argument(spec_.id + " controlled jointly: action has " + std::to_string(action.size()) +
                                  " entries, expected " + std::to_string(spec_.action_dim) +
                                  " (every agent's action in agent order)");
    }
    std::size_t offset = 0;
    const std::vector<int>& dims = team_->spec().action_dims;
    for (std::size_t i = 0; i < dims.size(); ++i) {
      actions_[i] = action.subspan(offset, static_cast<std::size_t>(dims[i]));
      offset += static_cast<std::size_t>(dims[i]);
    }
    const MultiAgentStepResult team = team_->step(actions_);
    const double agents = static_cast<double>(team.rewards.size());
    StepResult result;
    result.observation = concatenate(team.observations);
    for (const double reward : team.rewards) result.reward += reward;
    result.reward /= agents;
    for (const double cost : team.costs) result.cost += cost;
    result.cost /= agents;
    for (CostTerm& term : cost_terms_) term.value = 0;
    for (const std::span<const CostTerm> terms : team.cost_terms) {
      for (std::size_t t = 0; t < cost_terms_.size(); ++t) cost_terms_[t].value += terms[t].value / agents;
    }
    result.cost_terms = cost_terms_;
    result.terminated = team.terminated;
    result.truncated = team.truncated;
    return result;
  }

  EnvState state() const override {
    one_robot("state");
    return team_->body_states().front();
  }

  void teleport_agent(const Vec3&) override {
    throw std::logic_error(spec_.id + " controlled jointly cannot teleport its robots");
  }

 private:
  std::span<const double> concatenate(std::span<const std::span<const double>> observations) {
    std::size_t offset = 0;
    for (const std::span<const double> observation : observations) {
      std::copy(observation.begin(), observation.end(), observation_.begin() + static_cast<std::ptrdiff_t>(offset));
      offset += observation.size();
    }
    return observation_;
  }

  void one_robot(const char* call) const {
    if (team_->spec().bodies != 1) {
      throw std::logic_error(std::string(call) + ": " + spec_.id + " controlled jointly has " +
                             std::to_string(team_->spec().bodies) +
                             " robots; use the multi-agent environment (make_multi_agent) for one layout or "
                             "state per robot");
    }
  }

  std::unique_ptr<MultiAgentEnv> team_;
  EnvSpec spec_;
  std::vector<double> observation_;
  std::vector<CostTerm> cost_terms_;
  std::vector<std::span<const double>> actions_;
};

}  // namespace

std::unique_ptr<Env> make_joint_control(std::unique_ptr<MultiAgentEnv> team) {
  if (team == nullptr) throw std::invalid_argument("make_joint_control: no multi-agent environment");
  return std::make_unique<JointControlEnv>(std::move(team));
}

}  // namespace bsg::envs
