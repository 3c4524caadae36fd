#include "envs/tasks/run_task.h"

#include <algorithm>
#include <cmath>

#include "envs/tasks/layout_checks.h"

namespace bsg::envs {

double run_potential(double x, double y) {
  const double dx = x - 1000.0;
  return -60.0 * std::sqrt(dx * dx + y * y);
}

RunTask::RunTask(World& /*world*/, Agent& agent, const EnvDescription& description)
    : agent_(agent),
      y_limit_(description.run_y_limit),
      speed_limit_(description.run_speed_limit),
      spawn_range_(description.run_spawn_range),
      count_outside_bounds_(description.count_outside_bounds),
      count_velocity_violation_(description.count_velocity_violation) {}

void RunTask::sample_layout(Rng& rng, Layout& layout) {
  const double x = uniform(rng, -spawn_range_, spawn_range_);
  const double y = uniform(rng, -spawn_range_, spawn_range_);
  const AgentTraits& traits = agent_.traits();
  layout.agent_position = {x, y, traits.initial_position.z()};
  // Run never re-orients the agent (the Car keeps facing world −x, docs/environments.md#kept-quirks, item 17).
  const btQuaternion q = agent_.orientation();
  layout.agent_orientation = to_quat(q);
  layout.phi_prev = run_potential(x, y);
}

void RunTask::place(const Layout& layout, double /*clock_seconds*/) {
  require_unused_fields(layout, "Run", {"phi_prev"});
  agent_.set_base_pose(to_bt(layout.agent_position), to_bt(layout.agent_orientation));
  // Φ_prev is stored before the reset's engine step (golden README).
  phi_prev_ = layout.phi_prev.value_or(
      run_potential(layout.agent_position[0], layout.agent_position[1]));
}

TaskOutcome RunTask::evaluate(Rng& /*rng*/) {
  const btVector3 p = agent_.position();
  const btVector3 v = agent_.linear_velocity();
  const double phi = run_potential(p.x(), p.y());
  TaskOutcome outcome;
  outcome.reward = phi - phi_prev_ + agent_.specific_reward();
  phi_prev_ = phi;
  const double speed_xy = std::sqrt(v.x() * v.x() + v.y() * v.y());
  terms_[0].value = std::abs(p.y()) > y_limit_ ? 1.0 : 0.0;
  terms_[1].value = speed_xy > speed_limit_ ? 1.0 : 0.0;
  outcome.cost = std::min(1.0, (count_outside_bounds_ ? terms_[0].value : 0.0) +
                                   (count_velocity_violation_ ? terms_[1].value : 0.0));
  return outcome;
}

void RunTask::write_state(EnvState& state) const { state.phi_prev = phi_prev_; }

void RunTask::add_markings(std::vector<Marking>& out) const {
  // The lane edges along the whole 500 m plane (docs/environments.md#worlds).
  constexpr double kHalfLength = 250;
  for (const double y : {-y_limit_, y_limit_}) {
    out.push_back({Marking::Kind::kSafetyBoundary, {-kHalfLength, y, 0}, {kHalfLength, y, 0}, 0, 0,
                   true});
  }
}

}  // namespace bsg::envs
