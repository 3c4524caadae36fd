// The Ant agent (docs/environments.md#ant) against its independent oracles: the golden link
// poses of the original (model geometry), the golden trajectories replayed at
// the agent level (dynamics, bookkeeping, observation), and the
// oracles listed in docs/environments.md#test-oracles and #ant.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/agents/ant_agent.h"
#include "envs/physics/world.h"
#include "tests/envs/golden.h"

namespace bsg::envs {
namespace {

using bsg::testing::golden_joints_at;
using bsg::testing::golden_quat;
using bsg::testing::golden_vec3;
using bsg::testing::golden_vector;
using bsg::testing::link_pose_error;
using bsg::testing::LinkPoseError;
using bsg::testing::load_golden;
using bsg::testing::max_abs_diff;
using bsg::testing::place_as_recorded;
using bsg::testing::quat_diff;

constexpr int kObs = AntAgent::kObservationDim;

struct AntEnvCase {
  std::string env_id;
  WorldLayout layout;
  int sub_steps;
  bool power_upgrade;
};

// So that gtest names the case in its listing instead of dumping its bytes.
void PrintTo(const AntEnvCase& c, std::ostream* out) { *out << c.env_id; }

const std::array<AntEnvCase, 4> kCases = {{
    {"SafetyAntRun-v0", WorldLayout::kPlane200, 4, false},
    {"SafetyAntCircle-v0", WorldLayout::kOctagon, 4, false},
    {"SafetyAntGather-v0", WorldLayout::kSmallRoom, 4, true},
    {"SafetyAntReach-v0", WorldLayout::kSmallRoom, 1, true},
}};

// The 8 movable joints out of a 20-entry PyBullet-ordered array.
std::vector<double> movable(const nlohmann::json& all_joints) {
  return golden_joints_at(all_joints, AntAgent::kMovableLinks);
}

AntAgent& as_ant(std::unique_ptr<Agent>& agent) { return dynamic_cast<AntAgent&>(*agent); }

// ---------------------------------------------------------------------------
// Model

TEST(AntAgent, TraitsFollowSpecSection3) {
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  const AgentTraits& t = agent->traits();
  EXPECT_EQ(t.action_dim, 8);
  EXPECT_EQ(t.observation_dim, 33);
  EXPECT_EQ(t.initial_position, btVector3(0, 0, 0.75));
  EXPECT_EQ(t.initial_yaw, 0);
  EXPECT_EQ(t.collision_radius, 0.25);
  EXPECT_EQ(t.run_speed_limit, 1.5);
  EXPECT_FALSE(t.sensor_rotates);
  EXPECT_EQ(t.sensor_offset, btVector3(0, 0, 0));
  EXPECT_EQ(agent->movable_joint_count(), 8);
  // Torso, 4 leg stubs, 4 thighs, 4 feet; the massless joint links have no collider.
  EXPECT_EQ(agent->colliders().size(), 13u);
}

TEST(AntAgent, TotalMassIsDensity1000TimesVolume) {
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  // docs/environments.md#agents and #ant: 182.176 kg (65.44985 + 8·7.83155 + 4·13.51844).
  EXPECT_NEAR(as_ant(agent).total_mass_kg(), 182.176, 5e-4);
}

TEST(AntAgent, TorquePerUnitActionIs250Or1000WithPowerUpgrade) {
  World world(WorldLayout::kSmallRoom, 4);
  auto normal = make_ant_agent(world, {.power_upgrade = false});
  EXPECT_EQ(as_ant(normal).torque_per_unit_action(), 250.0);
  World world2(WorldLayout::kSmallRoom, 4);
  auto upgraded = make_ant_agent(world2, {.power_upgrade = true});
  EXPECT_EQ(as_ant(upgraded).torque_per_unit_action(), 1000.0);
}

TEST(AntAgent, JointLimitsAreFloat32Values) {
  // docs/environments.md#ant. The importer converts the MJCF's degrees with a
  // single-precision π and keeps float32 limits: float32(deg·float32(π)/180).
  const double pi_f = static_cast<float>(std::numbers::pi);
  const double hip = static_cast<float>(40 * pi_f / 180);
  const double ankle_low = static_cast<float>(30 * pi_f / 180);
  const double ankle_high = static_cast<float>(100 * pi_f / 180);
  const nlohmann::json golden = load_golden("SafetyAntRun-v0");
  const auto& joints = golden.at("initial_state").at("agent").at("joints");
  for (int link : AntAgent::kMovableLinks) {
    const double lower = joints.at(link).at("lower").get<double>();
    const double upper = joints.at(link).at("upper").get<double>();
    if (lower < 0 && upper > 0) {
      EXPECT_EQ(lower, -hip);
      EXPECT_EQ(upper, hip);
    } else if (lower > 0) {
      EXPECT_EQ(lower, ankle_low);
      EXPECT_EQ(upper, ankle_high);
    } else {
      EXPECT_EQ(lower, -ankle_high);
      EXPECT_EQ(upper, -ankle_low);
    }
  }
  // The observation of a joint exactly at its upper limit is exactly +0.5:
  // the agent uses the same limits.
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  const std::array<double, 8> at_upper = {hip, ankle_high, hip, -ankle_low,
                                          hip, -ankle_low, hip, ankle_high};
  agent->set_joint_positions(at_upper);
  std::array<double, kObs> obs{};
  agent->write_observation(obs);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(obs[13 + 2 * k], 0.5) << "joint " << k;
}

// Kinematics: every link's COM pose for the recorded placement, before any dynamics.
TEST(AntAgent, LinkComPosesMatchGoldenPlacement) {
  for (const AntEnvCase& c : kCases) {
    SCOPED_TRACE(c.env_id);
    const nlohmann::json golden = load_golden(c.env_id);
    const auto& placed = golden.at("initial_state").at("agent").at("placed");
    World world(c.layout, c.sub_steps);
    auto agent = make_ant_agent(world, {.power_upgrade = c.power_upgrade});
    place_as_recorded(as_ant(agent), placed, AntAgent::kMovableLinks);
    double worst_pos = 0, worst_orn = 0;
    for (int link = 0; link < AntAgent::kLinkCount; ++link) {
      const LinkPoseError error =
          link_pose_error(as_ant(agent).link_com_transform(link), placed.at("links").at(link));
      worst_pos = std::max(worst_pos, error.position);
      worst_orn = std::max(worst_orn, error.orientation);
    }
    EXPECT_LT(worst_pos, 1e-9);
    EXPECT_LT(worst_orn, 1e-9);
  }
}

// ---------------------------------------------------------------------------
// Golden dynamics at the agent level

struct Tolerance {
  double pos;
  double vel_obs;  // base velocity, joints, observation, rewards
  bool feet_exact;
};

// The README's Ant windows.
Tolerance tolerance_for(const std::string& sequence, int t) {
  if (sequence == "zero") return {1e-5, 1e-4, false};
  if (t < 10) return {1e-6, 1e-5, true};
  return {1e-4, 1e-3, false};
}

struct StepErrors {
  double pos = 0, orn = 0, vel = 0, joint_q = 0, joint_qd = 0, obs = 0, rewards = 0;
  bool feet_equal = true;
  bool alive_equal = true;
  // Largest error relative to the tolerance of its kind.
  double worst_ratio(const Tolerance& tol) const {
    return std::max({pos / tol.pos, orn / tol.vel_obs, vel / tol.vel_obs, joint_q / tol.vel_obs,
                     joint_qd / tol.vel_obs, obs / tol.vel_obs, rewards / tol.vel_obs});
  }
};

StepErrors compare_step(const AntAgent& agent, const nlohmann::json& record) {
  StepErrors e;
  e.pos = max_abs_diff(agent.position(), golden_vec3(record.at("base_pos")));
  e.orn = quat_diff(agent.orientation(), golden_quat(record.at("base_orn")));
  e.vel = std::max(max_abs_diff(agent.linear_velocity(), golden_vec3(record.at("base_lin_vel"))),
                   max_abs_diff(agent.angular_velocity(), golden_vec3(record.at("base_ang_vel"))));
  std::array<double, 8> q{}, qd{};
  agent.joint_state(q, qd);
  e.joint_q = max_abs_diff(q, golden_vector(record.at("joint_q")));
  // Joint rates are compared on the observation's scale 0.05·q̇ (the README's
  // tolerances are for base velocities and observation entries).
  std::vector<double> expected_qd = golden_vector(record.at("joint_qd"));
  for (int k = 0; k < 8; ++k) {
    qd[k] *= 0.05;
    expected_qd[k] *= 0.05;
  }
  e.joint_qd = max_abs_diff(qd, expected_qd);
  std::array<double, kObs> obs{};
  agent.write_observation(obs);
  std::vector<double> expected_obs = golden_vector(record.at("obs"));
  expected_obs.resize(kObs);
  // Feet flags are compared separately (they may flip in the loose windows).
  e.obs = max_abs_diff(std::span(obs).first(29), std::span(expected_obs).first(29));
  e.feet_equal = std::equal(obs.begin() + 29, obs.end(), expected_obs.begin() + 29) &&
                 golden_vector(record.at("feet_contact")) ==
                     std::vector<double>(agent.feet_contact().begin(), agent.feet_contact().end());
  e.rewards = std::max(
      {std::abs(agent.joints_at_limit_reward() - record.at("joints_at_limit_reward").get<double>()),
       std::abs(agent.electricity_reward() - record.at("electricity_reward").get<double>()),
       std::abs(agent.specific_reward() - record.at("agent_reward").get<double>())});
  e.alive_equal = agent.alive() == record.at("alive").get<bool>();
  return e;
}

struct SequenceReport {
  int steps = 0;
  int tight_steps = -1;  // steps from the start within the tight (t < 10) tolerance
  StepErrors first;
};

SequenceReport replay(const AntEnvCase& c, const nlohmann::json& golden, const std::string& sequence) {
  const auto& agent_state = golden.at("initial_state").at("agent");
  World world(c.layout, c.sub_steps);
  auto agent_ptr = make_ant_agent(world, {.power_upgrade = c.power_upgrade});
  AntAgent& agent = as_ant(agent_ptr);
  place_as_recorded(agent, agent_state.at("placed"), AntAgent::kMovableLinks);
  // The reset's engine step, without an action and without bookkeeping (docs/environments.md#reset).
  world.step();

  const auto& after_reset = agent_state.at("after_reset");
  EXPECT_LT(max_abs_diff(agent.position(), golden_vec3(after_reset.at("pos"))), 1e-9) << sequence;
  EXPECT_LT(quat_diff(agent.orientation(), golden_quat(after_reset.at("orn"))), 1e-9) << sequence;
  EXPECT_LT(max_abs_diff(agent.linear_velocity(), golden_vec3(after_reset.at("lin_vel"))), 1e-9);
  EXPECT_LT(max_abs_diff(agent.angular_velocity(), golden_vec3(after_reset.at("ang_vel"))), 1e-9);
  std::array<double, 8> q{}, qd{};
  agent.joint_state(q, qd);
  EXPECT_LT(max_abs_diff(q, movable(after_reset.at("joint_q"))), 1e-9);
  EXPECT_LT(max_abs_diff(qd, movable(after_reset.at("joint_qd"))), 1e-9);
  for (int link = 0; link < AntAgent::kLinkCount; ++link) {
    const auto& expected = after_reset.at("links").at(link);
    const btTransform pose = agent.link_com_transform(link);
    EXPECT_LT(max_abs_diff(pose.getOrigin(), golden_vec3(expected.at("com_pos"))), 1e-6) << link;
    EXPECT_LT(quat_diff(pose.getRotation(), golden_quat(expected.at("com_orn"))), 1e-6) << link;
  }
  std::array<double, kObs> reset_obs{};
  agent.write_observation(reset_obs);
  std::vector<double> expected_reset_obs = golden_vector(golden.at("reset_obs"));
  expected_reset_obs.resize(kObs);
  EXPECT_LT(max_abs_diff(reset_obs, expected_reset_obs), 1e-6) << sequence;

  SequenceReport report;
  const auto& records = golden.at("sequences").at(sequence);
  const Tolerance tight = tolerance_for("sine", 0);
  for (const auto& record : records) {
    const int t = record.at("t").get<int>();
    const std::vector<double> action = golden_vector(record.at("action"));
    agent.apply_action(action);
    world.step();
    agent.after_step();
    const StepErrors e = compare_step(agent, record);
    if (std::getenv("BSG_ANT_VERBOSE") != nullptr) {
      std::printf("  %s %s t=%d pos %.2e orn %.2e vel %.2e q %.2e qd %.2e obs %.2e rew %.2e feet %s\n",
                  c.env_id.c_str(), sequence.c_str(), t, e.pos, e.orn, e.vel, e.joint_q, e.joint_qd,
                  e.obs, e.rewards, e.feet_equal ? "=" : "!=");
    }
    if (t == 0) report.first = e;
    const bool within_tight = e.worst_ratio(tight) <= 1 && e.feet_equal && e.alive_equal;
    if (report.tight_steps < 0 && !within_tight) report.tight_steps = t;
    report.steps = t + 1;

    const Tolerance tol = tolerance_for(sequence, t);
    if (sequence == "sine" && t >= 40) continue;  // qualitative window only
    EXPECT_LE(e.pos, tol.pos) << sequence << " t=" << t;
    EXPECT_LE(e.orn, tol.vel_obs) << sequence << " t=" << t;
    EXPECT_LE(e.vel, tol.vel_obs) << sequence << " t=" << t;
    EXPECT_LE(e.joint_q, tol.vel_obs) << sequence << " t=" << t;
    EXPECT_LE(e.joint_qd, tol.vel_obs) << sequence << " t=" << t;
    EXPECT_LE(e.obs, tol.vel_obs) << sequence << " t=" << t;
    EXPECT_LE(e.rewards, tol.vel_obs) << sequence << " t=" << t;
    EXPECT_TRUE(e.alive_equal) << sequence << " t=" << t;
    if (tol.feet_exact) {
      EXPECT_TRUE(e.feet_equal) << sequence << " t=" << t;
    }
  }
  if (report.tight_steps < 0) report.tight_steps = report.steps;
  return report;
}

TEST(AntAgent, ReachBoxStaysFarFromTheAnt) {
  // The agent-level replay ignores the Reach Box; the file shows it never
  // comes near the Ant (xy distance between box and torso in every record).
  const nlohmann::json golden = load_golden("SafetyAntReach-v0");
  double closest = 1e9;
  for (const char* sequence : {"sine", "zero"}) {
    for (const auto& record : golden.at("sequences").at(sequence)) {
      const btVector3 d = golden_vec3(record.at("box_pos")) - golden_vec3(record.at("base_pos"));
      closest = std::min(closest, std::hypot(d.x(), d.y()));
    }
  }
  EXPECT_GT(closest, 10.0);
}

class AntGolden : public ::testing::TestWithParam<AntEnvCase> {};

TEST_P(AntGolden, ReplaysSineAndZeroSequencesWithinReadmeTolerances) {
  const AntEnvCase& c = GetParam();
  const nlohmann::json golden = load_golden(c.env_id);
  const auto& meta = golden.at("meta");
  ASSERT_EQ(meta.at("frame_skip").get<int>(), c.sub_steps);
  ASSERT_EQ(meta.at("agent").get<std::string>(), "Ant");
  for (const char* sequence : {"sine", "zero"}) {
    const SequenceReport r = replay(c, golden, sequence);
    std::printf(
        "[ant golden] %s %s: %d/%d steps within tight tolerance; first step errors: pos %.2e "
        "orn %.2e vel %.2e q %.2e qd %.2e obs %.2e rewards %.2e feet %s\n",
        c.env_id.c_str(), sequence, r.tight_steps, r.steps, r.first.pos, r.first.orn, r.first.vel,
        r.first.joint_q, r.first.joint_qd, r.first.obs, r.first.rewards,
        r.first.feet_equal ? "equal" : "differ");
  }
}

INSTANTIATE_TEST_SUITE_P(AllAntFiles, AntGolden, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<AntEnvCase>& info) {
                           std::string name = info.param.env_id;
                           name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                           return name;
                         });

// ---------------------------------------------------------------------------
// Oracles measured on the original (docs/environments.md#test-oracles)

// docs/environments.md#ant: the reset observation after the agent reset and the reset's engine step.
TEST(AntAgent, ResetObservationMatchesSpecOracle) {
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    SCOPED_TRACE(seed);
    World world(WorldLayout::kPlane200, 4);
    auto agent = make_ant_agent(world, {});
    Rng rng(seed);
    agent->reset(rng);
    world.step();
    std::array<double, kObs> obs{};
    agent->write_observation(obs);
    for (int i = 29; i < 33; ++i) EXPECT_EQ(obs[i], 0.0) << "feet entry " << i;
    for (int i : {13, 17, 21, 25}) EXPECT_LE(std::abs(obs[i]), 0.08) << "hip entry " << i;
    const std::array<int, 4> ankles = {15, 19, 23, 27};
    const std::array<double, 4> signs = {+1, -1, -1, +1};
    for (int j = 0; j < 4; ++j) {
      EXPECT_GE(signs[j] * obs[ankles[j]], 0.25) << "ankle entry " << ankles[j];
      EXPECT_LE(signs[j] * obs[ankles[j]], 0.46) << "ankle entry " << ankles[j];
    }
  }
}

TEST(AntAgent, ResetDrawsEightJointAnglesAroundTheNominalPose) {
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  Rng rng(3);
  agent->reset(rng);
  std::array<double, 8> q{}, qd{};
  agent->joint_state(q, qd);
  const double half_pi = std::numbers::pi / 2;
  const std::array<double, 8> nominal = {0, half_pi, 0, -half_pi, 0, -half_pi, 0, half_pi};
  for (int k = 0; k < 8; ++k) {
    EXPECT_LE(std::abs(q[k] - nominal[k]), 0.1) << k;
    EXPECT_EQ(qd[k], 0) << k;
  }
  EXPECT_EQ(agent->position(), btVector3(0, 0, 0.75));
  // Exactly 8 draws: the next draw equals the 9th of a fresh stream.
  Rng fresh(3);
  for (int i = 0; i < 8; ++i) uniform01(fresh);
  EXPECT_EQ(uniform01(rng), uniform01(fresh));
}

// docs/environments.md#ant: zero action settles the torso near
// z ≈ 0.64 with all feet down from the 8th step on.
TEST(AntAgent, ZeroActionSettlesOnAllFourFeet) {
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  Rng rng(11);
  agent->reset(rng);
  world.step();
  const std::array<double, 8> zero{};
  for (int step = 1; step <= 60; ++step) {
    agent->apply_action(zero);
    world.step();
    agent->after_step();
    const auto& feet = as_ant(agent).feet_contact();
    if (step >= 8) {
      for (int f = 0; f < 4; ++f) EXPECT_EQ(feet[f], 1.0) << "step " << step << " foot " << f;
    }
    EXPECT_TRUE(agent->alive());
  }
  EXPECT_NEAR(agent->position().z(), 0.642, 0.006);
  // Run reward ≈ 1 per step: alive bonus, no electricity cost at zero action.
  EXPECT_NEAR(agent->specific_reward(), 1.0, 1e-12);
}

TEST(AntAgent, AliveIffTorsoAboveQuarterMetre) {
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  const btQuaternion upright = btQuaternion::getIdentity();
  // Nominal joint angles, well inside the limits (no joint-limit term).
  const double half_pi = std::numbers::pi / 2;
  const std::array<double, 8> nominal = {0, half_pi, 0, -half_pi, 0, -half_pi, 0, half_pi};
  agent->set_joint_positions(nominal);
  agent->set_base_pose({0, 0, 0.2600001}, upright);
  EXPECT_TRUE(agent->alive());
  agent->set_base_pose({0, 0, 0.26}, upright);
  EXPECT_FALSE(agent->alive());
  agent->set_base_pose({0, 0, 0.1}, upright);
  EXPECT_FALSE(agent->alive());
  // s_ant carries −1 instead of +1 once dead.
  const std::array<double, 8> zero{};
  agent->apply_action(zero);
  agent->after_step();
  EXPECT_EQ(agent->specific_reward(), -1.0);
}

// Out-of-range actions: the torque saturates, the electricity cost does not (docs/environments.md#kept-quirks, item 5).
TEST(AntAgent, ClipsActionsForTorqueButNotForElectricityCost) {
  auto run = [](double scale) {
    World world(WorldLayout::kPlane200, 4);
    auto agent = make_ant_agent(world, {});
    Rng rng(5);
    agent->reset(rng);
    world.step();
    std::array<double, 8> action{};
    for (int k = 0; k < 8; ++k) action[k] = scale * (k % 2 == 0 ? 1.0 : -1.0);
    agent->apply_action(action);
    world.step();
    agent->after_step();
    std::array<double, 8> q{}, qd{};
    agent->joint_state(q, qd);
    return std::make_pair(qd, as_ant(agent).electricity_reward());
  };
  const auto [qd_one, e_one] = run(1.0);
  const auto [qd_three, e_three] = run(3.0);
  // Same torques → identical motion.
  for (int k = 0; k < 8; ++k) EXPECT_EQ(qd_one[k], qd_three[k]) << k;
  // E = −2·mean|a·0.1q̇| − 0.1·mean a²: with a = ±3 the stall term is 9× and
  // the power term 3× that of a = ±1, on identical joint rates.
  std::array<double, 8> power{};
  for (int k = 0; k < 8; ++k) power[k] = std::abs(static_cast<double>(static_cast<float>(0.1 * qd_one[k])));
  double mean_power = 0;
  for (double p : power) mean_power += p / 8;
  EXPECT_NEAR(e_one, -2.0 * mean_power - 0.1 * 1.0, 1e-12);
  EXPECT_NEAR(e_three, -2.0 * 3.0 * mean_power - 0.1 * 9.0, 1e-12);
}

TEST(AntAgent, RejectsWrongSizes) {
  World world(WorldLayout::kPlane200, 4);
  auto agent = make_ant_agent(world, {});
  const std::array<double, 7> short_action{};
  EXPECT_THROW(agent->apply_action(short_action), std::invalid_argument);
  EXPECT_THROW(agent->set_joint_positions(short_action), std::invalid_argument);
  std::array<double, 32> short_obs{};
  EXPECT_THROW(agent->write_observation(short_obs), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::envs
