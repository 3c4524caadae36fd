// A registry's map from id to description, and its lookup, shared by the
// single-agent registry (registry.h) and the multi-agent one
// (multi_agent_registry.cpp): built once from lists of descriptions, an id
// registered twice is a programming error, an unknown id an error listing the
// valid ones.
#pragma once

#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace bsg::envs {

// Every description of `lists` by its name; std::logic_error naming a name
// registered twice (`kind`: "environment", "multi-agent environment").
template <typename Description>
std::map<std::string, Description> id_map(std::initializer_list<std::vector<Description>> lists,
                                          std::string_view kind) {
  std::map<std::string, Description> result;
  for (const auto& list : lists) {
    for (const Description& description : list) {
      if (!result.emplace(description.name, description).second) {
        throw std::logic_error(std::string(kind) + " registered twice: " + description.name);
      }
    }
  }
  return result;
}

// The description registered as `id`; std::invalid_argument listing the valid ids.
template <typename Description>
const Description& find_id(const std::map<std::string, Description>& entries, const std::string& id,
                           std::string_view kind) {
  const auto found = entries.find(id);
  if (found == entries.end()) {
    std::string valid;
    for (const auto& [name, entry] : entries) valid += (valid.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown " + std::string(kind) + " id '" + id + "'; valid ids: " + valid);
  }
  return found->second;
}

}  // namespace bsg::envs
