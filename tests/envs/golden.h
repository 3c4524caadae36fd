// Access to the golden trajectories of the original suite (tests/data/golden/,
// a copy of shared/golden/; its README says what every field means and which
// tolerances the original's own sensitivity allows).
#pragma once

#include <fstream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>
#include <nlohmann/json.hpp>

namespace bsg::testing {

inline nlohmann::json load_golden(const std::string& env_id) {
  const std::string path = std::string(BSG_TEST_DATA_DIR) + "/golden/" + env_id + ".json";
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot open golden file " + path);
  return nlohmann::json::parse(file);
}

inline btVector3 golden_vec3(const nlohmann::json& value) {
  return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>()};
}

// Golden quaternions are [x, y, z, w].
inline btQuaternion golden_quat(const nlohmann::json& value) {
  return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>(),
          value.at(3).get<double>()};
}

inline std::vector<double> golden_vector(const nlohmann::json& value) {
  return value.get<std::vector<double>>();
}

// Largest absolute entry-wise difference; throws on a size mismatch.
inline double max_abs_diff(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) {
    throw std::runtime_error("size mismatch: " + std::to_string(a.size()) + " vs " +
                             std::to_string(b.size()));
  }
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

inline double max_abs_diff(const btVector3& a, const btVector3& b) {
  return std::max({std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())});
}

}  // namespace bsg::testing
