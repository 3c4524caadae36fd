// ConfigError: the one exception type of the configuration code. Its message
// names the input at fault: the key, the value, and the file:line:column or
// the `--set` argument it came from.
#pragma once

#include <stdexcept>
#include <string>

namespace bsg {

class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace bsg
