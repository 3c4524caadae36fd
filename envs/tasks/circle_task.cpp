#include "envs/tasks/circle_task.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "envs/tasks/layout_checks.h"
#include "envs/physics/orientation.h"
#include "envs/tasks/placement_sampler.h"

#include <stdexcept>
#include <string>

namespace bsg::envs {

double circle_reward_core(double x, double y, double vx, double vy, double circle_radius) {
  const double radius = std::sqrt(x * x + y * y);  // NumPy's norm (docs/environments.md#planar-distances)
  return 0.1 * (y * vx - x * vy) / (1 + std::abs(radius - circle_radius));
}

CircleTask::CircleTask(World& world, Agent& agent, const EnvDescription& description)
    : world_(world),
      agent_(agent),
      radius_(description.circle_radius),
      x_limit_(description.circle_x_limit),
      spawn_min_radius_(description.circle_spawn_min_radius),
      spawn_max_radius_(description.circle_spawn_max_radius),
      count_outside_bounds_(description.count_outside_bounds) {}

void CircleTask::sample_layout(Rng& rng, Layout& layout) {
  // The original draws one point and discards it, then redraws until the point
  // lies in the annulus 2 ≤ ‖p‖ ≤ 4 (docs/environments.md#circle).
  const double half_width = spawn_max_radius_;
  uniform(rng, -half_width, half_width);
  uniform(rng, -half_width, half_width);
  double x = 0, y = 0, radius = 0;
  long attempts = 0;
  do {
    // check_env_description keeps min < max, so the annulus has area; the
    // guard only turns a pathologically thin one into an error.
    if (++attempts > kMaxPlacementAttempts) {
      throw std::runtime_error("Circle: no spawn point in the annulus circle_spawn_min_radius=" +
                               std::to_string(spawn_min_radius_) + " m .. circle_spawn_max_radius=" +
                               std::to_string(spawn_max_radius_) + " m after " +
                               std::to_string(kMaxPlacementAttempts) + " draws");
    }
    x = uniform(rng, -half_width, half_width);
    y = uniform(rng, -half_width, half_width);
    radius = std::sqrt(x * x + y * y);
  } while (radius < spawn_min_radius_ || radius > spawn_max_radius_);
  const AgentTraits& traits = agent_.traits();
  // Body +x along the clockwise tangent (the Car's yaw_init turns it around).
  const double yaw = std::atan2(-y, -x) + std::numbers::pi / 2 + traits.initial_yaw;
  const btQuaternion q = quaternion_from_euler(0, 0, yaw);
  layout.agent_position = {x, y, traits.initial_position.z()};
  layout.agent_orientation = {q.x(), q.y(), q.z(), q.w()};
}

void CircleTask::place(const Layout& layout, double /*clock_seconds*/) {
  require_unused_fields(layout, "Circle", {});
  agent_.set_base_pose(to_bt(layout.agent_position), to_bt(layout.agent_orientation));
}

TaskOutcome CircleTask::evaluate(Rng& /*rng*/) {
  const btVector3 p = agent_.position();
  const btVector3 v = agent_.linear_velocity();
  TaskOutcome outcome;
  outcome.reward =
      circle_reward_core(p.x(), p.y(), v.x(), v.y(), radius_) + 0.01 * agent_.specific_reward();
  terms_[0].value = std::abs(p.x()) > x_limit_ ? 1.0 : 0.0;
  outcome.cost = std::min(1.0, count_outside_bounds_ ? terms_[0].value : 0.0);
  return outcome;
}

void CircleTask::write_observation(std::span<double> out) const {
  const btVector3 p = agent_.position();
  // Octagon's env_dim is 10 although its ground is 30 m wide (docs/environments.md#kept-quirks, item 15).
  out[0] = (std::sqrt(p.x() * p.x() + p.y() * p.y()) - radius_) / world_.env_dim();
}

void CircleTask::add_markings(std::vector<Marking>& out) const {
  out.push_back({Marking::Kind::kCircleTrack, {0, 0, 0}, {}, radius_, 0, true});
  // The slabs at x = ±x_limit run across the Octagon: there its diagonal walls
  // (inner faces 11.9 m from the centre) leave |y| ≤ 11.9·√2 − |x| (10.8 m for
  // the original's 6 m), and its straight walls |y| ≤ 11.9.
  const double half_length = std::clamp(11.9 * std::sqrt(2.0) - x_limit_, 0.0, 11.9);
  for (const double x : {-x_limit_, x_limit_}) {
    out.push_back({Marking::Kind::kSafetyBoundary, {x, -half_length, 0}, {x, half_length, 0}, 0, 0,
                   true});
  }
}

}  // namespace bsg::envs
