// Rendering speed: frames per second of the default camera at 480×360 and
// 64×64 for SafetyBallCircle-v0, SafetyCarReach-v0 and SafetyAntGather-v0
// (one env step between frames, not timed), by wall clock and by the
// process's CPU time (every thread, Mesa's rasteriser threads included); and
// the step rate of an environment beside a constructed but idle renderer
// against one without, in alternating rounds. Printed, never asserted.
// LP_NUM_THREADS=1 (set here unless given) keeps Mesa's llvmpipe on one thread.
//   bsg_render_bench [FRAMES] [STEP_ROUNDS]
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "envs/env.h"
#include "render/env_renderer.h"

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Rate {
  double wall = 0;
  double cpu = 0;
};

Rate frames_per_second(const std::string& id, int width, int height, int frames) {
  bsg::render::EnvRenderer renderer({width, height, "default"});
  const auto env = bsg::envs::make(id);
  env->reset(0);
  const std::vector<double> zero(static_cast<size_t>(env->spec().action_dim), 0.0);
  bsg::render::Image image;
  renderer.render(*env, image);  // first frame builds the shape meshes
  double wall = 0, cpu = 0;
  for (int i = 0; i < frames; ++i) {
    if (env->step(zero).truncated) env->reset();
    const double w0 = wall_seconds(), c0 = cpu_seconds();
    renderer.render(*env, image);
    wall += wall_seconds() - w0;
    cpu += cpu_seconds() - c0;
  }
  return {frames / wall, frames / cpu};
}

// CPU seconds per step of `steps` zero-action steps.
double seconds_per_step(bsg::envs::Env& env, int steps) {
  const std::vector<double> zero(static_cast<size_t>(env.spec().action_dim), 0.0);
  const double c0 = cpu_seconds();
  for (int i = 0; i < steps; ++i) {
    if (env.step(zero).truncated) env.reset();
  }
  return (cpu_seconds() - c0) / steps;
}

}  // namespace

int main(int argc, char** argv) {
  setenv("LP_NUM_THREADS", "1", 0);
  const int frames = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 7;
  std::cout << "LP_NUM_THREADS=" << std::getenv("LP_NUM_THREADS") << ", " << frames
            << " frames per figure\n"
            << std::left << std::setw(24) << "id" << std::right << std::setw(10) << "size"
            << std::setw(14) << "frames/s" << std::setw(18) << "frames/CPU-s" << "\n";
  for (const std::string id : {"SafetyBallCircle-v0", "SafetyCarReach-v0", "SafetyAntGather-v0"}) {
    for (const auto& [w, h] : {std::pair{480, 360}, {64, 64}}) {
      const Rate rate = frames_per_second(id, w, h, frames);
      std::cout << std::left << std::setw(24) << id << std::right << std::setw(10)
                << (std::to_string(w) + "x" + std::to_string(h)) << std::fixed
                << std::setprecision(0) << std::setw(14) << rate.wall << std::setw(18) << rate.cpu
                << std::endl;
    }
  }
  // An idle renderer beside the environment: the step path is the same code,
  // so any difference is noise; alternating rounds, median of the ratios.
  const auto plain = bsg::envs::make("SafetyBallCircle-v0");
  const auto beside = bsg::envs::make("SafetyBallCircle-v0");
  bsg::render::EnvRenderer idle({480, 360, "default"});
  plain->reset(0);
  beside->reset(0);
  std::vector<double> ratios;
  double plain_total = 0, beside_total = 0;
  for (int r = 0; r < rounds; ++r) {
    const double a = seconds_per_step(*plain, 50000);
    const double b = seconds_per_step(*beside, 50000);
    plain_total += a;
    beside_total += b;
    ratios.push_back(b / a);
  }
  std::sort(ratios.begin(), ratios.end());
  std::cout << std::setprecision(3) << "SafetyBallCircle-v0 step, " << rounds
            << " rounds of 50000: " << 1e6 * plain_total / rounds << " us without a renderer, "
            << 1e6 * beside_total / rounds << " us beside an idle renderer (median ratio "
            << ratios[ratios.size() / 2] << ")\n";
  return 0;
}
