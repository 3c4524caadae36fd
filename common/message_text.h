// Untrusted text shown in an error message: a value from a run file, a line of
// a progress log. It is cut to a bounded length (an 8 MB value must not make a
// 16 MB error line) with the full length stated, and every byte that is not
// printable ASCII or part of valid UTF-8 is escaped, so a message never carries
// raw control bytes (a terminal's escape sequences) or invalid UTF-8.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace bsg {

inline constexpr std::size_t kMessageExcerptBytes = 120;

// `text` made printable: "\n", "\t", "\r", "\\" and "\xHH" for the other
// control bytes, DEL and bytes that are not valid UTF-8; valid UTF-8
// sequences (but C1 controls U+0080..U+009F) are kept. Cut after `max_bytes`
// bytes of `text` (at a character boundary) with "... (N bytes)" appended.
std::string printable_excerpt(std::string_view text, std::size_t max_bytes = kMessageExcerptBytes);

// A whole error message made safe to print: as printable_excerpt, but line
// ends are kept (messages may span lines) and the cut is at 8192 bytes.
std::string printable_message(std::string_view text);

// Names listed in a message: "a, b, c" ("" for none).
std::string comma_separated(const std::vector<std::string>& items);
std::string comma_separated(const std::vector<std::string_view>& items);

}  // namespace bsg
