// A GCC 12 wrong-code case that made a test fail on a Rocket Lake build
// machine (CMakeLists.txt, BSG_CODEGEN_OPTIONS): when moves and stores by
// pieces may be 256 bits wide (-mmove-max=256 -mstore-max=256, the default
// tuning for Cannon Lake and later Intel CPUs), the 32-byte constant below
// reaches the vector as a broadcast of its first element, {20, 20, 20, 20}:
// the wide-integer form of the constant omits its zero top 8 bytes and the
// broadcast check never sees them. Exit 0 when the four values arrive as
// written, 1 (printing them) otherwise.
#include <cstdio>
#include <vector>

namespace {

__attribute__((noinline)) int check(const std::vector<double>& values) {
  const double expected[4] = {20.0, 20.0, 20.0, 0.0};
  bool same = values.size() == 4;
  for (std::size_t i = 0; same && i < 4; ++i) same = values[i] == expected[i];
  if (same) return 0;
  std::printf("constant_store_probe: expected {20, 20, 20, 0}, got {");
  for (std::size_t i = 0; i < values.size(); ++i) std::printf("%s%g", i ? ", " : "", values[i]);
  std::printf("}\n");
  return 1;
}

}  // namespace

int main() { return check({20.0, 20.0, 20.0, 0.0}); }
