// Test helpers for resolving a run against the shipped configs/: a request
// for one environment and algorithm with --set arguments, and the message of
// the ConfigError it must raise.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "common/config_error.h"
#include "common/run_config_resolve.h"

namespace bsg::testing {

inline const std::filesystem::path kShippedConfigs = std::filesystem::path(BSG_SOURCE_DIR) / "configs";

inline RunConfigRequest shipped_request(const std::string& env_id, const std::string& alg,
                                        std::vector<std::string> sets) {
  RunConfigRequest request;
  request.configs_dir = kShippedConfigs;
  request.set_arguments = {"env_id=" + env_id, "alg=" + alg};
  request.set_arguments.insert(request.set_arguments.end(), sets.begin(), sets.end());
  return request;
}

// The request the config tests use most: SafetyBallCircle-v0 with `alg`.
inline RunConfigRequest ball_circle_request(const std::string& alg, std::vector<std::string> sets) {
  return shipped_request("SafetyBallCircle-v0", alg, std::move(sets));
}

inline std::string config_error_of(const RunConfigRequest& request) {
  try {
    resolve_run_config(request);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a ConfigError";
  return "";
}

}  // namespace bsg::testing
