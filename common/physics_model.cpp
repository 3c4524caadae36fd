#include "common/physics_model.h"

#include <stdexcept>
#include <string>

namespace bsg {

std::string_view to_string(PhysicsModel model) {
  return model == PhysicsModel::kLean ? "lean" : "faithful";
}

PhysicsModel parse_physics_model(std::string_view name) {
  if (name == "faithful") return PhysicsModel::kFaithful;
  if (name == "lean") return PhysicsModel::kLean;
  throw std::invalid_argument("unknown physics model '" + std::string(name) +
                              "'; valid: faithful, lean");
}

}  // namespace bsg
