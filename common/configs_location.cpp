#include "common/configs_location.h"

#include <cstdlib>
#include <system_error>
#include <utility>

#include "common/config_error.h"

namespace bsg {

namespace {

namespace fs = std::filesystem;

fs::path absolute_or_same(const fs::path& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  return error ? path : absolute.lexically_normal();
}

// "  2. at or above the current folder: /a/configs, /configs" for each place
// up to `last` (inclusive).
std::string places_tried(const std::vector<ConfigsPlace>& places, std::size_t last) {
  std::string text;
  for (std::size_t i = 0; i <= last && i < places.size(); ++i) {
    const ConfigsPlace& place = places[i];
    text += "\n  " + std::to_string(i + 1) + ". " + place.description + ": ";
    if (place.candidates.empty()) {
      text += place.unavailable_note.empty() ? std::string("nothing to look at")
                                             : place.unavailable_note;
    }
    for (std::size_t c = 0; c < place.candidates.size(); ++c) {
      text += (c == 0 ? "" : ", ") + place.candidates[c].string();
    }
  }
  return text;
}

}  // namespace

bool is_configs_dir(const fs::path& dir) {
  std::error_code error;
  return fs::is_directory(dir / "algorithms", error);
}

ConfigsPlace configs_at_or_above(const fs::path& start, std::string description) {
  ConfigsPlace place;
  place.description = std::move(description);
  fs::path dir = absolute_or_same(start);
  while (true) {
    place.candidates.push_back(dir / "configs");
    if (!dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  return place;
}

std::vector<ConfigsPlace> configs_search_places(const ConfigsSearchInputs& inputs) {
  if (!inputs.explicit_dir.empty()) {
    return {ConfigsPlace{"--configs", {absolute_or_same(inputs.explicit_dir)}, true, ""}};
  }
  std::vector<ConfigsPlace> places;
  if (!inputs.input_file.empty()) {
    const fs::path folder = absolute_or_same(inputs.input_file).parent_path();
    places.push_back(
        configs_at_or_above(folder, "at or above the " + inputs.input_kind + "'s folder"));
  }
  if (!inputs.current_dir.empty()) {
    places.push_back(configs_at_or_above(inputs.current_dir, "at or above the current folder"));
  }
  ConfigsPlace variable{"$BSG_CONFIGS", {}, true, "not set"};
  if (inputs.configs_variable && !inputs.configs_variable->empty()) {
    variable.candidates.push_back(absolute_or_same(*inputs.configs_variable));
  }
  places.push_back(std::move(variable));
  ConfigsPlace installed{
      "the installed configs", {}, false, "unknown (the program's location cannot be read)"};
  if (!inputs.installed_dir.empty())
    installed.candidates.push_back(absolute_or_same(inputs.installed_dir));
  places.push_back(std::move(installed));
  ConfigsPlace source{"the source tree's configs", {}, false, "unknown"};
  if (!inputs.source_dir.empty()) source.candidates.push_back(absolute_or_same(inputs.source_dir));
  places.push_back(std::move(source));
  return places;
}

LocatedConfigs locate_configs_dir(const std::vector<ConfigsPlace>& places) {
  for (std::size_t i = 0; i < places.size(); ++i) {
    const ConfigsPlace& place = places[i];
    for (const fs::path& candidate : place.candidates) {
      if (is_configs_dir(candidate)) return LocatedConfigs{candidate, place.description};
    }
    if (place.required && !place.candidates.empty()) {
      const std::string problem = place.description + " names " +
                                  place.candidates.front().string() +
                                  ", which is not a configs folder (it has no algorithms/ folder)";
      throw ConfigError(i == 0 ? problem
                               : problem + "; places tried, in order:" + places_tried(places, i));
    }
  }
  throw ConfigError(
      "no configs folder (one holding algorithms/ and envs/) was found; places tried, in order:" +
      places_tried(places, places.size() - 1) +
      "\nName one with --configs DIR or the environment variable BSG_CONFIGS=DIR.");
}

LocatedConfigs locate_configs_from_here(ConfigsSearchInputs inputs) {
  std::error_code error;
  inputs.current_dir = std::filesystem::current_path(error);
  if (const char* variable = std::getenv("BSG_CONFIGS")) inputs.configs_variable = variable;
  return locate_configs_dir(configs_search_places(inputs));
}

}  // namespace bsg
