// Minimal RFC 4180 CSV text: quoting a field that holds a comma, quote or
// newline (configuration names such as "target_kl=0.001,lambda_lr=0.01"
// do), and splitting a line back into fields.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bsg {

std::string csv_field(std::string_view text);

// Splits one line (without its newline); throws std::invalid_argument on an
// unterminated quote.
std::vector<std::string> parse_csv_fields(std::string_view line);

}  // namespace bsg
