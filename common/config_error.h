// ConfigError: the one exception type of the configuration code. Its message
// names the input at fault: the key, the value, and the file:line:column or
// the `--set` argument it came from.
#pragma once

#include <stdexcept>
#include <string>

#include "common/message_text.h"

namespace bsg {

class ConfigError : public std::runtime_error {
 public:
  // Untrusted text in the message (a value, a key, a file's bytes) is made
  // printable and the whole bounded (message_text.h).
  explicit ConfigError(const std::string& message) : std::runtime_error(printable_message(message)) {}
};

}  // namespace bsg
