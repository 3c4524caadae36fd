// The same state renders the same pixels: twice in one process, in a second
// renderer, and in a new process (`bsg envs --picture`); rendering leaves the
// simulation untouched (a rendered rollout is bit-identical to one that is not).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli/run_bsg.h"
#include "envs/env.h"
#include "envs/description/standard_descriptions.h"
#include "render/image_grid.h"
#include "render_test_support.h"

namespace bsg::render {
namespace {

TEST(RenderDeterminism, SameStateSamePixelsTwiceAndInASecondRenderer) {
  BSG_RENDERER_OR_SKIP(first, (RenderOptions{160, 120, "default"}));
  BSG_RENDERER_OR_SKIP(second, (RenderOptions{160, 120, "default"}));
  for (const std::string id : {"SafetyCarReach-v0", "SafetyAntGather-v0", "SafetyDroneRun-v0"}) {
    const auto env = envs::make(id);
    env->reset(11);
    const std::vector<double> action(static_cast<size_t>(env->spec().action_dim), 0.3);
    for (int i = 0; i < 20; ++i) env->step(action);
    Image a, b, c;
    first->render(*env, a);
    first->render(*env, b);
    second->render(*env, c);
    EXPECT_EQ(a.rgb, b.rgb) << id;
    EXPECT_EQ(a.rgb, c.rgb) << id;
  }
}

TEST(RenderDeterminism, ARendererReusedAcrossEnvironmentsDrawsWhatAFreshOneDraws) {
  // Environments made and destroyed one after the other reuse addresses:
  // nothing cached for one may be drawn for the next.
  BSG_RENDERER_OR_SKIP(shared, (RenderOptions{120, 90, "track"}));
  for (const std::string& id : envs::registered_ids()) {
    const auto env = envs::make(id);
    env->reset(2);
    Image reused, fresh;
    shared->render(*env, reused);
    EnvRenderer({120, 90, "track"}).render(*env, fresh);
    EXPECT_EQ(reused.rgb, fresh.rgb) << id;
  }
}

TEST(RenderDeterminism, ANewProcessDrawsTheSamePixels) {
  BSG_RENDERER_OR_SKIP(renderer, (RenderOptions{64, 48, "top"}));
  std::vector<Image> images;
  for (const envs::EnvDescription& description : envs::standard_descriptions()) {  // what --picture draws
    const auto env = envs::make(description);
    env->reset(7);
    renderer->render(*env, images.emplace_back());
  }
  const Image expected = image_grid(images, 4, 4);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("bsg_render_determinism_" + std::to_string(::getpid()) + ".png"))
                               .string();
  const testing::ProgramResult result =
      testing::run_bsg("envs --picture " + path + " --width 64 --height 48 --camera top --seed 7");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const Image written = testing::read_png(path);
  std::filesystem::remove(path);
  ASSERT_EQ(written.width, expected.width);
  ASSERT_EQ(written.height, expected.height);
  EXPECT_EQ(written.rgb, expected.rgb);
}

TEST(RenderDeterminism, RenderingLeavesTheSimulationBitIdentical) {
  BSG_RENDERER_OR_SKIP(renderer, (RenderOptions{64, 48, "track"}));
  for (const std::string id : {"SafetyBallCircle-v0", "SafetyCarGather-v0", "SafetyAntReach-v0"}) {
    const auto rendered = envs::make(id);
    const auto plain = envs::make(id);
    rendered->reset(4);
    plain->reset(4);
    Image image;
    std::vector<double> action(static_cast<size_t>(plain->spec().action_dim));
    for (int t = 0; t < 200; ++t) {
      for (size_t k = 0; k < action.size(); ++k) action[k] = std::sin(0.1 * t + static_cast<double>(k));
      renderer->render(*rendered, image);
      const envs::StepResult a = rendered->step(action);
      const std::vector<double> observation(a.observation.begin(), a.observation.end());
      const envs::StepResult b = plain->step(action);
      ASSERT_EQ(0, std::memcmp(observation.data(), b.observation.data(),
                               observation.size() * sizeof(double)))
          << id << " step " << t;
      ASSERT_EQ(a.reward, b.reward) << id << " step " << t;
      ASSERT_EQ(a.cost, b.cost) << id << " step " << t;
    }
  }
}

}  // namespace
}  // namespace bsg::render
