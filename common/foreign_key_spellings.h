// Other libraries' names for bsg's configuration keys (Stable-Baselines3, CleanRL, Spinning Up,
// Tianshou), so that an unknown key written as those libraries write it points to bsg's key with
// the same meaning instead of to the key closest in spelling ('tau' is polyak, not lam).
#pragma once

#include <span>
#include <string_view>

namespace bsg {

struct ForeignKeySpelling {
  std::string_view spelling;   // the other libraries' name
  std::string_view key;        // bsg's key of the same meaning
  std::string_view libraries;  // who spell it so, for the message
};

// Every spelling; each `key` is a key of the run configuration.
std::span<const ForeignKeySpelling> foreign_key_spellings();

// The row of `spelling`, or nullptr.
const ForeignKeySpelling* find_foreign_key_spelling(std::string_view spelling);

}  // namespace bsg
