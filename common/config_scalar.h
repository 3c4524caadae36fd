// Strict text <-> value conversions for configuration scalars. YAML leaves the
// type of a plain scalar to the reader; these decide it the same way for files
// and for `--set key=value`, and write reals so that they read back exactly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace bsg {

// YAML 1.2 core booleans plus yaml-cpp's spellings: true/false, yes/no, on/off
// (any case as yaml-cpp accepts: lower, Capitalised, UPPER).
std::optional<bool> parse_config_bool(std::string_view text);

// A decimal integer with an optional sign; no fraction, exponent or spaces.
std::optional<std::int64_t> parse_config_integer(std::string_view text);

// A finite decimal real (e.g. 0.01, 1e-4, 25); rejects nan/inf and hex.
std::optional<double> parse_config_real(std::string_view text);

// Shortest text that parses back to exactly `value` (std::to_chars).
std::string format_config_real(double value);

}  // namespace bsg
