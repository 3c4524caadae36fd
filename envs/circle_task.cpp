#include "circle_task.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "layout_checks.h"
#include "orientation.h"

namespace bsg::envs {

double circle_reward_core(double x, double y, double vx, double vy) {
  const double radius = std::sqrt(x * x + y * y);  // NumPy's norm (docs/environments.md#planar-distances)
  return 0.1 * (y * vx - x * vy) / (1 + std::abs(radius - kCircleRadius));
}

CircleTask::CircleTask(World& world, Agent& agent) : world_(world), agent_(agent) {}

void CircleTask::sample_layout(Rng& rng, Layout& layout) {
  // The original draws one point and discards it, then redraws until the point
  // lies in the annulus 2 ≤ ‖p‖ ≤ 4 (docs/environments.md#circle).
  uniform(rng, -4, 4);
  uniform(rng, -4, 4);
  double x = 0, y = 0, radius = 0;
  do {
    x = uniform(rng, -4, 4);
    y = uniform(rng, -4, 4);
    radius = std::sqrt(x * x + y * y);
  } while (radius < 2 || radius > 4);
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
      circle_reward_core(p.x(), p.y(), v.x(), v.y()) + 0.01 * agent_.specific_reward();
  terms_[0].value = std::abs(p.x()) > kCircleXLimit ? 1.0 : 0.0;
  outcome.cost = std::min(1.0, terms_[0].value);
  return outcome;
}

void CircleTask::write_observation(std::span<double> out) const {
  const btVector3 p = agent_.position();
  // Octagon's env_dim is 10 although its ground is 30 m wide (docs/environments.md#kept-quirks, item 15).
  out[0] = (std::sqrt(p.x() * p.x() + p.y() * p.y()) - kCircleRadius) / world_.env_dim();
}

TaskBlueprint circle_task() {
  return {"Circle", WorldLayout::kOctagon, 4, false,
          [](World& world, Agent& agent, const EnvOptions&) {
            return std::make_unique<CircleTask>(world, agent);
          }};
}

void CircleTask::add_markings(std::vector<Marking>& out) const {
  out.push_back({Marking::Kind::kCircleTrack, {0, 0, 0}, {}, kCircleRadius, 0, true});
  // The slabs at x = ±6 run across the Octagon: at |x| = 6 its walls (inner
  // faces 11.9 m from the centre) leave |y| ≤ 11.9·√2 − 6 ≈ 10.8.
  constexpr double kHalfLength = 10.8;
  for (const double x : {-kCircleXLimit, kCircleXLimit}) {
    out.push_back({Marking::Kind::kSafetyBoundary, {x, -kHalfLength, 0}, {x, kHalfLength, 0}, 0, 0,
                   true});
  }
}

}  // namespace bsg::envs
