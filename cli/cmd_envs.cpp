// `bsg envs [--json]`: the registered environments with their observation and
// action sizes, episode length and cost limit (docs/environments.md#the-sixteen-environments, report Table 3).
// `bsg envs --describe ID [--set key=value]...`: the full resolved description
// of one environment as YAML (docs/environments.md#environment-descriptions), with
// its observation and action sizes as comments.
// `bsg envs --picture FILE [--width W] [--height H] [--camera C] [--seed S]`:
// a PNG of every environment after reset(S), 4 per row (docs/rendering.md).
#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "env_set_arguments.h"
#include "envs/env.h"
#include "envs/standard_envs.h"
#include "render/env_renderer.h"
#include "render/image_grid.h"
#include "render/png_file.h"

namespace bsg::cli {
namespace {

int list_envs(bool json) {
  nlohmann::json list = nlohmann::json::array();
  if (!json) {
    std::cout << std::left << std::setw(24) << "id" << std::right << std::setw(8) << "obs"
              << std::setw(8) << "act" << std::setw(10) << "steps" << std::setw(12) << "cost_limit"
              << "\n";
  }
  for (const std::string& id : envs::registered_ids()) {
    const envs::EnvSpec spec = envs::make(id)->spec();
    if (json) {
      list.push_back({{"id", spec.id},
                      {"agent", spec.agent},
                      {"task", spec.task},
                      {"observation_dim", spec.observation_dim},
                      {"action_dim", spec.action_dim},
                      {"max_episode_steps", spec.max_episode_steps},
                      {"cost_limit", spec.cost_limit}});
    } else {
      std::cout << std::left << std::setw(24) << spec.id << std::right << std::setw(8)
                << spec.observation_dim << std::setw(8) << spec.action_dim << std::setw(10)
                << spec.max_episode_steps << std::setw(12) << spec.cost_limit << "\n";
    }
  }
  if (json) std::cout << list.dump(2) << "\n";
  return 0;
}

struct PictureArguments {
  std::string path;
  render::RenderOptions render;
  std::uint64_t seed = 0;
};

int picture_envs(const PictureArguments& args) {
  render::EnvRenderer renderer(args.render);
  std::vector<render::Image> images;
  // The 16 standard environments, 4 per row (the README's picture).
  for (const envs::EnvDescription& description : envs::standard_descriptions()) {
    const std::unique_ptr<envs::Env> env = envs::make(description);
    env->reset(args.seed);
    renderer.render(*env, images.emplace_back());
  }
  render::write_png(args.path, render::image_grid(images, 4, 4));
  std::cout << "wrote " << args.path << " (" << images.size() << " environments)\n";
  return 0;
}

int describe_env(const std::string& id, const std::vector<std::string>& set_arguments) {
  const envs::EnvDescription description = envs::describe(id, parse_env_set_arguments(set_arguments));
  const envs::EnvSpec spec = envs::make(description)->spec();
  std::cout << "# " << spec.id << ": observation " << spec.observation_dim << ", action "
            << spec.action_dim << "\n"
            << envs::to_yaml(description);
  return 0;
}

}  // namespace

void add_envs_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand(
      "envs", "List the registered environments: observation/action sizes, episode length, cost limit");
  auto json = std::make_shared<bool>(false);
  auto picture = std::make_shared<PictureArguments>();
  auto describe = std::make_shared<std::string>();
  auto set = std::make_shared<std::vector<std::string>>();
  auto* json_flag = command->add_flag("--json", *json, "print a JSON array");
  auto* describe_option = command->add_option(
      "--describe", *describe, "print the full description of one environment id as YAML");
  command->add_option("--set", *set, "--describe: change a parameter (repeatable), e.g. --set bombs=12")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->needs(describe_option);
  json_flag->excludes(describe_option);
  auto* picture_option =
      command->add_option("--picture", picture->path, "write a PNG of every environment after reset, 4 per row");
  picture_option->excludes(describe_option)->excludes(json_flag);
  command->add_option("--width", picture->render.width, "--picture: width of one environment's image")
      ->capture_default_str();
  command->add_option("--height", picture->render.height, "--picture: height of one environment's image")
      ->capture_default_str();
  command->add_option("--camera", picture->render.camera, "--picture: default, track or top")
      ->capture_default_str();
  command->add_option("--seed", picture->seed, "--picture: reset seed")->capture_default_str();
  command->callback([&run, json, describe, set, picture]() {
    if (!describe->empty()) {
      run = [describe, set]() { return describe_env(*describe, *set); };
      return;
    }
    run = [json, picture]() {
      return picture->path.empty() ? list_envs(*json) : picture_envs(*picture);
    };
  });
}

}  // namespace bsg::cli
