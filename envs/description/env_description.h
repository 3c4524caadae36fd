// An environment as data (design.md "Environments"; the report's §4.1
// EnvironmentBuilder): agent, task, world, physics and every count, size,
// range and radius the tasks and agents use, each defaulting to the original's
// value. The 16 standard ids are such values (standard_descriptions.h) and
// make(description) builds every environment, standard or custom, by one path.
// Keys, types and checks of every field are one table (env_parameters.h);
// docs/environments.md#environment-descriptions lists them with units.
//
// Parameters (key: default; "/" separates the standard values by task or agent):
//   name                      Safety<agent><task>-v0   id reported by spec()
//   agent                     Ball                     Ball, Car, Drone, Ant
//   task                      Circle                   Circle, Gather, Reach, Run
//   world                     Octagon/SmallRoom/SmallRoom/Plane200 (Circle/Gather/Reach/Run)
//   time_step                 1/240 s; 1/60 s (Reach)  one internal physics step
//   frame_skip                4; 1 (Reach)             internal steps per env step
//   max_episode_steps         250/500/500/1000 (Ball/Car/Drone/Ant)
//   cost_limit                25/0.2/10/25 (Circle/Gather/Reach/Run); AntReach 25
//   power_upgrade             false; true (Gather, Reach)  Car and Ant motors
//   clip_actions              false (Car only: the original's car does not clip)
//   circle_radius             7 m                      Circle
//   circle_x_limit            6 m                      Circle: cost when |x| > limit
//   circle_spawn_min_radius   2 m                      Circle
//   circle_spawn_max_radius   4 m                      Circle
//   placement_half_width      7 m                      Gather, Reach: square of draws
//   max_altitude              2 m                      Gather, Reach: cost_out_of_range
//   apples, bombs             8, 8                     Gather
//   gather_detection_distance 1 m                      Gather
//   apple_reward              10                       Gather
//   death_reward              -10                      Gather
//   gather_agent_clearance    1 m                      Gather
//   gather_spacing            2 m                      Gather
//   gather_sensor_bins        16                       Gather
//   gather_sensor_range       10 m                     Gather
//   goal_radius               1.3 m                    Reach
//   goal_bonus                5                        Reach
//   goal_max_speed            5 m/s                    Reach
//   goal_respawn_clearance    1.5 m                    Reach
//   reach_spacing             2.5 m                    Reach
//   reach_reward_scale        1                        Reach: factor on (d_prev − d)
//   goal_scheme               random                   Reach: random or corners
//   zones                     8                        Reach
//   zone_type                 puddle; pillar (Drone)   Reach
//   zone_radius               1 m; 0.45 m (pillar)     Reach
//   zone_layout               random                   Reach: random or barrier (fork CarReach)
//   obstacle_clearance_from   spawn                    Reach: spawn, or stale (the fork)
//   box                       true                     Reach: the moving Box
//   box_circle_radius         0.7 m                    Reach
//   lidar_rays, lidar_range   24, 5 m                  Reach
//   reach_sensor_bins         24                       Reach
//   reach_sensor_range        5 m                      Reach
//   run_y_limit               2 m                      Run: avenue half-width
//   run_speed_limit           2.5 m/s Ball, 1.5 m/s others  Run
//   run_spawn_range           0.01 m                   Run
//   count_* (cost terms)      true                     which cost terms count
#pragma once

#include <array>
#include <string>

namespace bsg::envs {

// zone_layout barrier: the fork's CarReach map, puddle centres (x, y) [m] in
// the fork's order, a wall of puddles around x in [-2, 2] with openings between
// the spawn (-6, 6) and the goal corner (6, 6).
inline constexpr std::array<std::array<double, 2>, 17> kBarrierZones = {{
    {-1, -3}, {-1, -1}, {-1, 5}, {-1, 7}, {-1, 9}, {1, -3}, {1, -1}, {1, 5}, {1, 7}, {1, 9},
    {1, 3}, {-5, 0}, {-6, -1}, {5, 0}, {6, -1}, {-1, -6}, {1, -6}}};
inline constexpr std::array<double, 2> kBarrierSpawn = {-6, 6};

struct EnvDescription {
  // --- what is assembled ---
  std::string name = "SafetyBallCircle-v0";
  std::string agent = "Ball";
  std::string task = "Circle";
  std::string world = "Octagon";

  // --- physics and episode ---
  double time_step = 1.0 / 240.0;  // [s] one internal physics step
  int frame_skip = 4;              // internal steps per environment step
  int max_episode_steps = 250;
  double cost_limit = 25;          // d of the report's Table 3, per episode
  bool power_upgrade = false;      // Car and Ant: stronger motors (Gather, Reach)
  bool clip_actions = false;       // Car: clip actions to [-1, 1] (the fork does)

  // --- Circle ---
  double circle_radius = 7;            // [m] R of the reward
  double circle_x_limit = 6;           // [m] cost when |x| > limit
  double circle_spawn_min_radius = 2;  // [m]
  double circle_spawn_max_radius = 4;  // [m] also the half-width of the draw square
  bool count_outside_bounds = true;    // Circle, Run

  // --- Gather and Reach: the arena ---
  double placement_half_width = 7;  // [m] int(0.7·env_dim) of the SmallRoom
  double max_altitude = 2;          // [m] cost_out_of_range above it
  bool count_out_of_range = true;

  // --- Gather ---
  int apples = 8;
  int bombs = 8;
  double gather_detection_distance = 1;  // [m] planar, strict
  double apple_reward = 10;
  double death_reward = -10;             // replaces the step reward when the agent dies
  double gather_agent_clearance = 1;     // [m] draws closer to the agent are rejected
  double gather_spacing = 2;             // [m] between objects (3-d)
  int gather_sensor_bins = 16;
  double gather_sensor_range = 10;       // [m]
  bool count_gathered_bombs = true;

  // --- Reach ---
  double goal_radius = 1.3;             // [m]
  double goal_bonus = 5;
  double goal_max_speed = 5;            // [m/s] 3-d speed below which a goal counts
  double goal_respawn_clearance = 1.5;  // [m] new goal from agent, Box and zones
  double reach_spacing = 2.5;           // [m] agent–goal, agent–obstacle, obstacle–obstacle/goal
  double reach_reward_scale = 1;        // factor on d_prev − d
  std::string goal_scheme = "random";   // random, or corners (the fork's two corners)
  int zones = 8;
  std::string zone_type = "puddle";     // puddle or pillar
  // random, or barrier: the fork's CarReach map (17 fixed puddles, spawn at (−6, 6))
  std::string zone_layout = "random";
  // spawn: obstacles keep reach_spacing from this episode's spawn and drawn
  // goal; stale: from where agent and goal stood before the reset moved them
  // (the fork: its Reach samples obstacles first; docs/environments.md#the-fork-variant)
  std::string obstacle_clearance_from = "spawn";
  double zone_radius = 1;               // [m]
  bool box = true;
  double box_circle_radius = 0.7;       // [m] radius of the Box's pivot circle
  int lidar_rays = 24;
  double lidar_range = 5;               // [m]
  int reach_sensor_bins = 24;
  double reach_sensor_range = 5;        // [m]
  bool count_collisions = true;

  // --- Run ---
  double run_y_limit = 2;         // [m] avenue half-width
  double run_speed_limit = 2.5;   // [m/s] planar speed
  double run_spawn_range = 0.01;  // [m] spawn x, y ~ U(−range, range)
  bool count_velocity_violation = true;

  bool operator==(const EnvDescription&) const = default;

  // Seconds per environment step: time_step · frame_skip.
  double env_step_seconds() const { return time_step * frame_skip; }
};

}  // namespace bsg::envs
