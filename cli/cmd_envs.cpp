// `bsg envs [--json]`: the registered environments with their observation and
// action sizes, episode length and cost limit (docs/environments.md#the-sixteen-environments, report Table 3),
// then the multi-agent ids (docs/multi_agent.md#ids) in a section of their own.
// `--json` keeps to the single-agent array its readers expect; `--multi-agent`
// lists only the multi-agent ids (with `--json`, as their own array).
// `bsg envs --describe ID [--set key=value]...`: the full resolved description
// of one environment, single- or multi-agent, as YAML
// (docs/environments.md#environment-descriptions), with its sizes as comments.
// `bsg envs --picture FILE [--width W] [--height H] [--camera C] [--seed S]`:
// a PNG of every environment after reset(S), 4 per row (docs/rendering.md).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "env_set_arguments.h"
#include "envs/env.h"
#include "envs/multi_agent_env.h"
#include "envs/standard_envs.h"
#include "render/env_renderer.h"
#include "render/image_grid.h"
#include "render/png_file.h"

namespace bsg::cli {
namespace {

// "10,12" for per-agent sizes.
std::string joined(const std::vector<int>& values) {
  std::string text;
  for (const int value : values) text += (text.empty() ? "" : ",") + std::to_string(value);
  return text;
}

nlohmann::json multi_agent_entry(const envs::MultiAgentSpec& spec) {
  return {{"id", spec.id},
          {"agent", spec.agent},
          {"task", spec.task},
          {"partition", spec.partition},
          {"bodies", spec.bodies},
          {"agents", spec.agent_count()},
          {"observation_dims", spec.observation_dims},
          {"action_dims", spec.action_dims},
          {"state_dim", spec.state_dim},
          {"max_episode_steps", spec.max_episode_steps},
          {"cost_limit", spec.cost_limit},
          {"team_reward", spec.team_reward},
          {"team_cost", spec.team_cost}};
}

// The multi-agent ids: sizes per agent, agent order.
int list_multi_agent_envs(bool json) {
  nlohmann::json list = nlohmann::json::array();
  if (!json) {
    std::cout << "\nmulti-agent (bsg.parallel_env; obs and act per agent)\n"
              << std::left << std::setw(24) << "id" << std::right << std::setw(8) << "agents"
              << std::setw(14) << "obs" << std::setw(10) << "act" << std::setw(8) << "state"
              << std::setw(10) << "steps" << std::setw(12) << "cost_limit" << "\n";
  }
  for (const std::string& id : envs::multi_agent_ids()) {
    const envs::MultiAgentSpec spec = envs::make_multi_agent(id)->spec();
    if (json) {
      list.push_back(multi_agent_entry(spec));
    } else {
      std::cout << std::left << std::setw(24) << spec.id << std::right << std::setw(8)
                << spec.agent_count() << std::setw(14) << joined(spec.observation_dims)
                << std::setw(10) << joined(spec.action_dims) << std::setw(8) << spec.state_dim
                << std::setw(10) << spec.max_episode_steps << std::setw(12) << spec.cost_limit << "\n";
    }
  }
  if (json) std::cout << list.dump(2) << "\n";
  return 0;
}

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
  if (json) {
    std::cout << list.dump(2) << "\n";
    return 0;
  }
  return list_multi_agent_envs(false);
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

int describe_multi_agent_env(const std::string& id, const std::vector<std::string>& set_arguments) {
  const envs::MultiAgentDescription description =
      envs::describe_multi_agent(id, parse_env_set_arguments(set_arguments));
  const envs::MultiAgentSpec spec = envs::make_multi_agent(description)->spec();
  std::cout << "# " << spec.id << ": " << spec.agent_count() << " agents, observation "
            << joined(spec.observation_dims) << ", action " << joined(spec.action_dims) << ", state "
            << spec.state_dim << "\n"
            << envs::to_multi_agent_yaml(description);
  return 0;
}

int describe_env(const std::string& id, const std::vector<std::string>& set_arguments) {
  const std::vector<std::string> multi_agent = envs::multi_agent_ids();
  if (std::find(multi_agent.begin(), multi_agent.end(), id) != multi_agent.end()) {
    return describe_multi_agent_env(id, set_arguments);
  }
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
  auto multi_agent = std::make_shared<bool>(false);
  auto* json_flag = command->add_flag("--json", *json, "print a JSON array (single-agent ids)");
  auto* multi_agent_flag = command->add_flag(
      "--multi-agent", *multi_agent, "list only the multi-agent ids (with --json: their JSON array)");
  auto* describe_option = command->add_option(
      "--describe", *describe, "print the full description of one environment id as YAML");
  command->add_option("--set", *set, "--describe: change a parameter (repeatable), e.g. --set bombs=12")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->needs(describe_option);
  json_flag->excludes(describe_option);
  multi_agent_flag->excludes(describe_option);
  auto* picture_option =
      command->add_option("--picture", picture->path, "write a PNG of every environment after reset, 4 per row");
  picture_option->excludes(describe_option)->excludes(json_flag)->excludes(multi_agent_flag);
  command->add_option("--width", picture->render.width, "--picture: width of one environment's image")
      ->capture_default_str();
  command->add_option("--height", picture->render.height, "--picture: height of one environment's image")
      ->capture_default_str();
  command->add_option("--camera", picture->render.camera, "--picture: default, track or top")
      ->capture_default_str();
  command->add_option("--seed", picture->seed, "--picture: reset seed")->capture_default_str();
  command->callback([&run, json, multi_agent, describe, set, picture]() {
    if (!describe->empty()) {
      run = [describe, set]() { return describe_env(*describe, *set); };
      return;
    }
    if (*multi_agent) {
      run = [json]() { return list_multi_agent_envs(*json); };
      return;
    }
    run = [json, picture]() {
      return picture->path.empty() ? list_envs(*json) : picture_envs(*picture);
    };
  });
}

}  // namespace bsg::cli
