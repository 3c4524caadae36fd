#include "envs/description/fork_descriptions.h"

#include "envs/description/standard_descriptions.h"

namespace bsg::envs {
namespace {

// Episode length of the fork's registrations for Circle and Run (Gather and
// Reach keep the standard lengths).
int fork_episode_steps(const EnvDescription& d) {
  const bool circle = d.task == "Circle";
  if (d.agent == "Ball") return circle ? 200 : 100;
  if (d.agent == "Ant") return circle ? 500 : 200;
  return circle ? 300 : 200;  // Car, Drone
}

EnvDescription fork_description(const EnvDescription& standard) {
  EnvDescription d = standard;
  d.name = "Safety" + d.agent + d.task + "-fork";
  d.clip_actions = d.agent == "Car";
  if (d.task == "Circle") {
    d.time_step = 1.0 / 60.0;
    d.frame_skip = 6;
    d.max_episode_steps = fork_episode_steps(d);
  } else if (d.task == "Run" || d.task == "Gather") {
    d.time_step = 1.0 / 120.0;
    d.frame_skip = d.agent == "Drone" ? 2 : 4;
    if (d.task == "Run") d.max_episode_steps = fork_episode_steps(d);
  } else {  // Reach
    d.time_step = 1.0 / 60.0;
    d.frame_skip = 4;
    d.reach_reward_scale = 3;
    d.goal_bonus = 30;
    d.goal_scheme = "corners";
    if (d.agent != "Car") {
      // The fork samples the Box and the zones before its reset moves agent
      // and goal, so they may lie on the new spawn or the goal corner.
      // (CarReach's fixed map overwrites the sample; it keeps the default.)
      d.obstacle_clearance_from = "stale";
    } else {
      // No Box: no obstacle with a collision shape, so no LIDAR either.
      d.box = false;
      d.lidar_rays = 0;
      d.zones = static_cast<int>(kBarrierZones.size());
      d.zone_layout = "barrier";
    }
  }
  return d;
}

}  // namespace

std::vector<EnvDescription> fork_descriptions() {
  std::vector<EnvDescription> list;
  for (const EnvDescription& standard : standard_descriptions()) list.push_back(fork_description(standard));
  return list;
}

}  // namespace bsg::envs
