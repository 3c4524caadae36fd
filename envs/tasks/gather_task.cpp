#include "envs/tasks/gather_task.h"

#include <algorithm>
#include <vector>

#include "envs/tasks/layout_checks.h"
#include "envs/tasks/placement_sampler.h"

namespace bsg::envs {

GatherTask::GatherTask(World& /*world*/, Agent& agent, const EnvDescription& description)
    : agent_(agent),
      description_(description),
      sensor_(description.gather_sensor_bins, description.gather_sensor_range),
      apples_(description.apples, description.gather_detection_distance),
      bombs_(description.bombs, description.gather_detection_distance) {}

void GatherTask::sample_layout(Rng& rng, Layout& layout) {
  // The agent starts at the origin with its initial orientation (docs/environments.md#gather).
  const AgentTraits& traits = agent_.traits();
  const btVector3 start(0, 0, traits.initial_position.z());
  layout.agent_position = to_vec3(start);
  layout.agent_orientation = to_quat(agent_.orientation());
  const int apples = description_.apples;
  const int bombs = description_.bombs;
  const std::vector<btVector3> positions = sample_obstacle_positions(
      rng, apples + bombs, start, std::nullopt, description_.gather_spacing,
      description_.gather_agent_clearance, description_.placement_half_width);
  layout.apples.clear();
  layout.bombs.clear();
  for (int i = 0; i < apples; ++i) layout.apples.push_back(to_vec3(positions[static_cast<size_t>(i)]));
  for (int i = apples; i < apples + bombs; ++i) {
    layout.bombs.push_back(to_vec3(positions[static_cast<size_t>(i)]));
  }
}

void GatherTask::place(const Layout& layout, double /*clock_seconds*/) {
  require_unused_fields(layout, "Gather", {"apples", "bombs"});
  require_count("Gather", "apples", layout.apples.size(), static_cast<size_t>(description_.apples));
  require_count("Gather", "bombs", layout.bombs.size(), static_cast<size_t>(description_.bombs));
  agent_.set_base_pose(to_bt(layout.agent_position), to_bt(layout.agent_orientation));
  placement_.clear();
  for (const Vec3& v : layout.apples) placement_.push_back(to_bt(v));
  apples_.place(placement_);
  placement_.clear();
  for (const Vec3& v : layout.bombs) placement_.push_back(to_bt(v));
  bombs_.place(placement_);
}

TaskOutcome GatherTask::evaluate(Rng& /*rng*/) {
  const btVector3 p = agent_.position();
  TaskOutcome outcome;
  // Reward first (docs/environments.md#one-step, item 6), no agent-specific term (docs/environments.md#kept-quirks, item 11).
  outcome.reward = description_.apple_reward * apples_.collect_near(p);
  if (!agent_.alive()) outcome.reward = description_.death_reward;
  terms_[0].value = bombs_.collect_near(p);
  terms_[1].value = p.z() > description_.max_altitude ? 1.0 : 0.0;
  outcome.cost = std::min(1.0, (description_.count_gathered_bombs ? terms_[0].value : 0.0) +
                                   (description_.count_out_of_range ? terms_[1].value : 0.0));
  outcome.ends_episode = apples_.active_count() == 0;
  return outcome;
}

void GatherTask::write_observation(std::span<double> out) const {
  const btVector3 p = agent_.position();
  const auto bins = static_cast<size_t>(sensor_.bins());
  // Collected apples and touched bombs are still sensed (docs/environments.md#kept-quirks, item 9).
  sensor_.measure(p, apples_.positions(), out.first(bins));
  sensor_.measure(p, bombs_.positions(), out.subspan(bins, bins));
}

void GatherTask::write_state(EnvState& state) const {
  state.apples_active.assign(apples_.active().begin(), apples_.active().end());
  state.bombs_active.assign(bombs_.active().begin(), bombs_.active().end());
}

void GatherTask::add_markings(std::vector<Marking>& out) const {
  // Spheres of radius 0.5 (docs/environments.md#obstacles).
  constexpr double kRadius = 0.5;
  const auto add = [&out](const Collectibles& objects, Marking::Kind kind) {
    for (int i = 0; i < objects.count(); ++i) {
      const auto index = static_cast<size_t>(i);
      out.push_back({kind, to_vec3(objects.positions()[index]), {}, kRadius, 0,
                     objects.active()[index]});
    }
  };
  add(apples_, Marking::Kind::kApple);
  add(bombs_, Marking::Kind::kBomb);
}

}  // namespace bsg::envs
