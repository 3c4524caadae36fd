// Seeded mutations of a valid input for the readers' fuzz tests: byte flips,
// inserted and deleted bytes, cuts, and (for text) swapped, repeated and
// dropped lines. The same seed gives the same inputs on every machine
// (std::mt19937_64 with integer draws only).
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace bsg::testing {

inline std::vector<std::string> split_lines_keeping_ends(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
    lines.push_back(text.substr(start, stop - start));
    start = stop;
  }
  return lines;
}

// One mutation of `input` chosen by `rng`; may equal `input` (rarely).
inline std::string mutate(const std::string& input, std::mt19937_64& rng) {
  std::string out = input;
  const auto draw = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n); };
  const int kind = static_cast<int>(rng() % 9);
  const char interesting[] = {'\0', '\n', ',', '-', '.', 'e', '9', '\x7f', '\xff', ' ', '"', '\r', 'n'};
  switch (kind) {
    case 0:  // flip one bit
      if (!out.empty()) out[draw(out.size())] ^= static_cast<char>(1u << draw(8));
      break;
    case 1:  // overwrite a byte with an interesting one
      if (!out.empty()) out[draw(out.size())] = interesting[draw(sizeof interesting)];
      break;
    case 2:  // insert a byte
      out.insert(draw(out.size() + 1), 1, interesting[draw(sizeof interesting)]);
      break;
    case 3:  // delete a run of bytes
      if (!out.empty()) {
        const std::size_t at = draw(out.size());
        out.erase(at, 1 + draw(std::min<std::size_t>(16, out.size() - at)));
      }
      break;
    case 4:  // cut the end
      out.resize(draw(out.size()));
      break;
    default: {  // line-level edits
      std::vector<std::string> lines = split_lines_keeping_ends(out);
      if (lines.size() < 2) break;
      const std::size_t a = draw(lines.size());
      const std::size_t b = draw(lines.size());
      if (kind == 5) std::swap(lines[a], lines[b]);
      if (kind == 6) lines.insert(lines.begin() + static_cast<long>(a), lines[b]);
      if (kind == 7) lines.erase(lines.begin() + static_cast<long>(a));
      if (kind == 8) {  // several byte edits on one line
        for (int i = 0; i < 3 && !lines[a].empty(); ++i) lines[a][draw(lines[a].size())] ^= 0x11;
      }
      out.clear();
      for (const std::string& line : lines) out += line;
    }
  }
  return out;
}

}  // namespace bsg::testing
