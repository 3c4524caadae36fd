#include "envs/assembly/multi_body_env.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "envs/assembly/assembled_env.h"
#include "envs/tasks/layout_checks.h"
#include "envs/tasks/placement_sampler.h"

namespace bsg::envs {
namespace {

constexpr int kRelativePositionDims = 2;  // (p_j − p_i)_xy per other robot

int single_observation_dim(const Body& body) {
  return body.agent->traits().observation_dim + body.task->observation_dim();
}

}  // namespace

MultiAgentSpec multi_body_spec(const MultiAgentDescription& d, const std::vector<Body>& bodies) {
  MultiAgentSpec spec;
  spec.id = d.name;
  spec.agent = d.env.agent;
  spec.task = d.env.task;
  spec.partition = d.partition;
  spec.bodies = static_cast<int>(bodies.size());
  const int others = spec.bodies - 1;
  for (size_t i = 0; i < bodies.size(); ++i) {
    spec.agent_names.push_back("agent_" + std::to_string(i));
    spec.observation_dims.push_back(single_observation_dim(bodies[i]) + kRelativePositionDims * others);
    spec.action_dims.push_back(bodies[i].agent->traits().action_dim);
    spec.state_dim += single_observation_dim(bodies[i]);
  }
  spec.max_episode_steps = d.env.max_episode_steps;
  spec.cost_limit = d.env.cost_limit;
  spec.team_reward = d.reward == "team";
  spec.team_cost = d.cost == "team";
  for (const CostTerm& term : bodies.front().task->cost_terms()) spec.cost_term_names.emplace_back(term.name);
  spec.cost_term_names.emplace_back("cost_agent_collisions");
  return spec;
}

MultiBodyEnv::MultiBodyEnv(const MultiAgentDescription& description, std::unique_ptr<World> world,
                           std::vector<Body> bodies)
    : spec_(multi_body_spec(description, bodies)),
      agent_spacing_(description.agent_spacing),
      count_agent_collisions_(description.count_agent_collisions),
      shared_hazards_(description.env.task == "Reach"),
      hazard_spacing_(description.env.reach_spacing),
      world_(std::move(world)),
      bodies_(std::move(bodies)),
      buffers_(spec_),
      body_rewards_(bodies_.size(), 0.0),
      body_costs_(bodies_.size(), 0.0) {
  for (const Body& body : bodies_) {
    for (const btCollisionObject* collider : body.agent->colliders()) all_colliders_.push_back(collider);
  }
}

bool MultiBodyEnv::clear_of_shared_hazards(const Layout& robot, const Layout& first) const {
  std::vector<Vec3> hazards = first.zones;
  if (first.box) hazards.push_back(first.box->position);
  for (const Vec3& hazard : hazards) {
    for (const Vec3& point : {robot.agent_position, robot.goal.value_or(robot.agent_position)}) {
      if (std::hypot(point[0] - hazard[0], point[1] - hazard[1]) < hazard_spacing_) return false;
    }
  }
  return true;
}

void MultiBodyEnv::sample_layouts(std::vector<Layout>& layouts) {
  for (size_t i = 0; i < bodies_.size(); ++i) {
    long attempts = 0;
    bool clear = false;
    while (!clear) {
      if (++attempts > kMaxPlacementAttempts) {
        throw std::runtime_error(spec_.id + ": no spawn for robot " + std::to_string(i) +
                                 " agent_spacing=" + std::to_string(agent_spacing_) +
                                 " m from the others after " + std::to_string(kMaxPlacementAttempts) +
                                 " draws");
      }
      layouts[i] = Layout{};
      bodies_[i].task->sample_layout(rng_, layouts[i]);
      clear = !shared_hazards_ || i == 0 || clear_of_shared_hazards(layouts[i], layouts[0]);
      for (size_t j = 0; j < i && clear; ++j) {
        const double dx = layouts[i].agent_position[0] - layouts[j].agent_position[0];
        const double dy = layouts[i].agent_position[1] - layouts[j].agent_position[1];
        clear = std::sqrt(dx * dx + dy * dy) >= agent_spacing_;
      }
    }
  }
}

std::span<const std::span<const double>> MultiBodyEnv::reset_impl(const std::vector<Layout>* injected) {
  // As AssembledEnv's reset (docs/environments.md#reset): no cached contacts,
  // every agent reset (its draws in robot order), then every placement, then
  // one engine step without actions.
  world_->forget_contacts();
  elapsed_steps_ = 0;
  for (Body& body : bodies_) body.agent->reset(rng_);
  std::vector<Layout> layouts(bodies_.size());
  if (injected != nullptr) {
    layouts = *injected;
    for (size_t i = 0; i < bodies_.size(); ++i) {
      if (!layouts[i].joint_positions.empty()) bodies_[i].agent->set_joint_positions(layouts[i].joint_positions);
    }
  } else {
    sample_layouts(layouts);
  }
  for (size_t i = 0; i < bodies_.size(); ++i) bodies_[i].task->place(layouts[i], 0);
  world_->step();
  has_reset_ = true;
  return observe();
}

std::span<const std::span<const double>> MultiBodyEnv::reset(std::uint64_t seed) {
  rng_.seed(seed);
  return reset_impl(nullptr);
}

std::span<const std::span<const double>> MultiBodyEnv::reset() { return reset_impl(nullptr); }

std::span<const std::span<const double>> MultiBodyEnv::reset_to(std::span<const Layout> layouts) {
  if (layouts.size() != bodies_.size()) {
    throw std::invalid_argument(spec_.id + ": reset_to needs one layout per robot (" +
                                std::to_string(bodies_.size()) + "), got " + std::to_string(layouts.size()));
  }
  for (size_t i = 0; i < layouts.size(); ++i) {
    require_valid_pose(layouts[i]);
    const auto joints = static_cast<size_t>(bodies_[i].agent->movable_joint_count());
    if (!layouts[i].joint_positions.empty() && layouts[i].joint_positions.size() != joints) {
      throw std::invalid_argument(spec_.id + ": layout " + std::to_string(i) + ": joint_positions needs " +
                                  std::to_string(joints) + " entries (or none), got " +
                                  std::to_string(layouts[i].joint_positions.size()));
    }
  }
  const std::vector<Layout> copy(layouts.begin(), layouts.end());
  return reset_impl(&copy);
}

bool MultiBodyEnv::touches_another_robot(size_t body) const {
  const std::span<const btCollisionObject* const> own = bodies_[body].agent->colliders();
  for (size_t other = 0; other < bodies_.size(); ++other) {
    if (other == body) continue;
    for (const btCollisionObject* collider : own) {
      if (world_->contact_points(collider, bodies_[other].agent->colliders()) > 0) return true;
    }
  }
  return false;
}

MultiAgentStepResult MultiBodyEnv::step(std::span<const std::span<const double>> actions) {
  check_multi_agent_actions(spec_, has_reset_, actions);
  // The single-agent order (docs/environments.md#one-step), every robot at each stage.
  ++elapsed_steps_;
  for (size_t i = 0; i < bodies_.size(); ++i) bodies_[i].agent->apply_action(actions[i]);
  for (Body& body : bodies_) body.task->before_physics(0);
  world_->step();
  for (Body& body : bodies_) body.agent->after_step();
  bool any_dead = false;
  bool any_ended = false;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const TaskOutcome outcome = bodies_[i].task->evaluate(rng_);
    const double collision = touches_another_robot(i) ? 1.0 : 0.0;
    std::span<CostTerm> terms = buffers_.cost_terms(static_cast<int>(i));
    const std::span<const CostTerm> task_terms = bodies_[i].task->cost_terms();
    for (size_t t = 0; t < task_terms.size(); ++t) terms[t].value = task_terms[t].value;
    terms.back().value = collision;
    body_rewards_[i] = outcome.reward;
    body_costs_[i] = std::min(1.0, outcome.cost + (count_agent_collisions_ ? collision : 0.0));
    any_dead = any_dead || !bodies_[i].agent->alive();
    any_ended = any_ended || outcome.ends_episode;
  }
  double team_reward = 0, team_cost = 0;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    team_reward += body_rewards_[i];
    team_cost += body_costs_[i];
  }
  for (size_t i = 0; i < bodies_.size(); ++i) {
    buffers_.rewards()[i] = spec_.team_reward ? team_reward : body_rewards_[i];
    buffers_.costs()[i] = spec_.team_cost ? team_cost : body_costs_[i];
  }
  observe();
  const bool terminated = any_dead || any_ended;
  const bool truncated = !terminated && elapsed_steps_ >= spec_.max_episode_steps;
  return buffers_.result(terminated, truncated);
}

std::span<const std::span<const double>> MultiBodyEnv::observe() {
  std::span<double> state = buffers_.state();
  size_t state_offset = 0;
  const double env_dim = world_->env_dim();
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const Body& body = bodies_[i];
    std::span<double> out = buffers_.observation(static_cast<int>(i));
    const auto agent_dim = static_cast<size_t>(body.agent->traits().observation_dim);
    const auto own_dim = static_cast<size_t>(single_observation_dim(body));
    body.agent->write_observation(out.first(agent_dim));
    body.task->write_observation(out.subspan(agent_dim, own_dim - agent_dim));
    std::copy_n(out.begin(), own_dim, state.begin() + static_cast<std::ptrdiff_t>(state_offset));
    state_offset += own_dim;
    const btVector3 p = body.agent->position();
    size_t next = own_dim;
    for (size_t j = 0; j < bodies_.size(); ++j) {
      if (j == i) continue;
      const btVector3 q = bodies_[j].agent->position();
      out[next++] = (q.x() - p.x()) / env_dim;
      out[next++] = (q.y() - p.y()) / env_dim;
    }
  }
  return buffers_.observations();
}

std::vector<EnvState> MultiBodyEnv::body_states() const {
  std::vector<EnvState> states;
  for (const Body& body : bodies_) states.push_back(snapshot_state(*body.agent, *body.task, elapsed_steps_));
  return states;
}

std::vector<Marking> MultiBodyEnv::markings() const {
  std::vector<Marking> markings;
  if (!shared_hazards_) {
    bodies_.front().task->add_markings(markings);  // every robot's task marks the same arena
    return markings;
  }
  // Reach: robot 0's hazards and goal, then every other robot's goal.
  for (const Body& body : bodies_) body.task->add_markings(markings);
  return markings;
}

}  // namespace bsg::envs
