// `bsg dataset info FILE [--plot FILE.png] [--json]`: what an offline dataset
// holds (docs/datasets.md#reading): transitions, complete episodes (and how
// many the environment ended), the ranges of the episodes' reward and cost
// returns, how many keep within the stored cost limit, and how it was made.
// --plot draws each episode's cost return against its reward return, the
// stored cost limit dashed (DSRL's picture of a dataset's reward-cost frontier).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "algos/offline/dataset_file.h"
#include "commands.h"
#include "render/png_file.h"
#include "render/scatter_plot.h"

namespace bsg::cli {
namespace {

struct DatasetInfoArguments {
  std::string file;
  std::string plot;
  bool json = false;
};

struct Range {
  double min = 0.0, mean = 0.0, max = 0.0;
};

Range range_of(const std::vector<double>& values) {
  Range r;
  if (values.empty()) return r;
  r.min = *std::min_element(values.begin(), values.end());
  r.max = *std::max_element(values.begin(), values.end());
  for (double v : values) r.mean += v;
  r.mean /= static_cast<double>(values.size());
  return r;
}

int dataset_info(const DatasetInfoArguments& args) {
  const algos::OfflineDataset dataset = algos::read_dataset_file(args.file);
  const std::vector<algos::DatasetEpisode> episodes = algos::dataset_episodes(dataset);
  std::vector<double> rewards, costs;
  std::size_t terminated = 0;
  for (const algos::DatasetEpisode& e : episodes) {
    rewards.push_back(e.reward_return);
    costs.push_back(e.cost_return);
    terminated += e.terminated ? 1 : 0;
  }
  const Range reward = range_of(rewards);
  const Range cost = range_of(costs);
  const auto limit_attribute = dataset.number_attributes.find("cost_limit");
  const std::optional<double> cost_limit =
      limit_attribute == dataset.number_attributes.end() ? std::nullopt : std::optional(limit_attribute->second);
  const std::size_t within = cost_limit ? static_cast<std::size_t>(std::count_if(costs.begin(), costs.end(), [&](double c) {
    return c <= *cost_limit;
  }))
                                        : 0;
  const auto text = [&](const std::string& key) {
    const auto it = dataset.text_attributes.find(key);
    return it == dataset.text_attributes.end() ? std::string("(not recorded)") : it->second;
  };
  if (!args.plot.empty()) {
    render::ScatterPlotOptions options;
    options.x_label = "cost";
    options.y_label = "return";
    options.vertical_line = cost_limit;
    render::write_png(args.plot, render::scatter_plot(costs, rewards, options));
  }
  if (args.json) {
    nlohmann::json out = {{"file", args.file},
                          {"transitions", dataset.size()},
                          {"episodes", episodes.size()},
                          {"terminated_episodes", terminated},
                          {"observation_dim", dataset.observation_dim},
                          {"action_dim", dataset.action_dim},
                          {"reward_return", {{"min", reward.min}, {"mean", reward.mean}, {"max", reward.max}}},
                          {"cost_return", {{"min", cost.min}, {"mean", cost.mean}, {"max", cost.max}}},
                          {"constraints", dataset.constraint_names}};
    if (cost_limit) {
      out["cost_limit"] = *cost_limit;
      out["episodes_within_cost_limit"] = within;
    }
    for (const auto& [key, value] : dataset.text_attributes) out["attributes"][key] = value;
    for (const auto& [key, value] : dataset.number_attributes) out["attributes"][key] = value;
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << args.file << ": " << text("env_id") << ", made by bsg " << text("bsg_version") << "\n"
            << "transitions " << dataset.size() << ", complete episodes " << episodes.size() << " ("
            << terminated << " ended by the environment)\n"
            << "observations " << dataset.observation_dim << ", actions " << dataset.action_dim << "\n"
            << "reward return min " << reward.min << ", mean " << reward.mean << ", max " << reward.max << "\n"
            << "cost return min " << cost.min << ", mean " << cost.mean << ", max " << cost.max << "\n";
  if (cost_limit) {
    std::cout << "cost limit " << *cost_limit << ": " << within << " of " << episodes.size()
              << " episodes within it\n";
  }
  if (dataset.constraint_names.size() > 1) {
    std::cout << "constraints";
    for (const std::string& name : dataset.constraint_names) std::cout << " " << name;
    std::cout << "\n";
  }
  std::cout << "policies:\n  " << text("policies") << "\n";
  if (!args.plot.empty()) std::cout << "wrote " << args.plot << "\n";
  return 0;
}

}  // namespace

void add_dataset_command(CLI::App& app, Action& run) {
  CLI::App* command = app.add_subcommand("dataset", "Offline datasets: bsg dataset info FILE");
  command->require_subcommand(1);
  CLI::App* info = command->add_subcommand(
      "info", "Transitions, episodes, return and cost ranges of a dataset file; --plot draws cost against return");
  auto args = std::make_shared<DatasetInfoArguments>();
  info->add_option("FILE", args->file, "an HDF5 dataset (bsg collect or DSRL)")->required();
  info->add_option("--plot", args->plot, "write the episodes' cost return against reward return as a PNG");
  info->add_flag("--json", args->json, "print JSON");
  info->callback([&run, args]() { run = [args]() { return dataset_info(*args); }; });
}

}  // namespace bsg::cli
