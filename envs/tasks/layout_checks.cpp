#include "envs/tasks/layout_checks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::envs {
namespace {

bool is_used(std::initializer_list<std::string_view> used, std::string_view field) {
  return std::find(used.begin(), used.end(), field) != used.end();
}

}  // namespace

void require_unused_fields(const Layout& layout, std::string_view task_name,
                           std::initializer_list<std::string_view> used) {
  const std::pair<std::string_view, bool> set_fields[] = {
      {"goal", layout.goal.has_value()},     {"box", layout.box.has_value()},
      {"zones", !layout.zones.empty()},      {"d_prev", layout.d_prev.has_value()},
      {"apples", !layout.apples.empty()},    {"bombs", !layout.bombs.empty()},
      {"phi_prev", layout.phi_prev.has_value()},
  };
  for (const auto& [field, set] : set_fields) {
    if (set && !is_used(used, field)) {
      throw std::invalid_argument("Layout field '" + std::string(field) + "' is not used by the " +
                                  std::string(task_name) + " task; leave it empty");
    }
  }
}

void require_count(std::string_view task_name, std::string_view field, size_t given,
                   size_t expected) {
  if (given != expected) {
    throw std::invalid_argument(std::string(task_name) + " layout: '" + std::string(field) +
                                "' needs " + std::to_string(expected) + " positions, got " +
                                std::to_string(given));
  }
}

void require_valid_pose(const Layout& layout) {
  for (double value : layout.agent_position) {
    if (!std::isfinite(value)) {
      throw std::invalid_argument("Layout: agent_position has a non-finite entry");
    }
  }
  const Quat& q = layout.agent_orientation;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!std::isfinite(norm) || std::abs(norm - 1) > 1e-6) {
    throw std::invalid_argument("Layout: agent_orientation must be a unit quaternion [x, y, z, w], "
                                "its norm is " + std::to_string(norm));
  }
}

}  // namespace bsg::envs
