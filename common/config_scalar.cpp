#include "common/config_scalar.h"

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

namespace bsg {

std::optional<bool> parse_config_bool(std::string_view text) {
  static constexpr std::array<std::string_view, 9> kTrue = {
      "true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"};
  static constexpr std::array<std::string_view, 9> kFalse = {
      "false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"};
  for (std::string_view word : kTrue) {
    if (text == word) return true;
  }
  for (std::string_view word : kFalse) {
    if (text == word) return false;
  }
  return std::nullopt;
}

std::optional<std::int64_t> parse_config_integer(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  std::int64_t value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::optional<double> parse_config_real(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = text.data() + text.size();
  // chars_format::general: fixed or scientific, never hex, never "inf"/"nan"
  // accepted as finite below.
  auto [ptr, error] = std::from_chars(text.data(), end, value, std::chars_format::general);
  if (error != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string format_config_real(double value) {
  std::array<char, 64> buffer{};
  auto [ptr, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  (void)error;  // 64 characters always suffice for a double
  std::string text(buffer.data(), ptr);
  // Keep a real looking like a real ("25" -> "25.0") so a reader sees its type.
  if (std::isfinite(value) && text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

}  // namespace bsg
