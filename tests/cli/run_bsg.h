// Runs the built `bsg` program from a test and captures its exit code and
// output, so that command-line behaviour is tested end to end.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <sys/wait.h>

namespace bsg::testing {

// The repository's root, and its configs folder as a command line's --configs
// option (with its leading space): shared, so that test files compiled as one
// batch define neither twice.
inline const std::filesystem::path kSource{BSG_SOURCE_DIR};
inline const std::string kConfigsOption = std::string(" --configs ") + BSG_SOURCE_DIR + "/configs";

struct ProgramResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing stdout and stderr together.
inline ProgramResult run_command(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot start: " + command);
  ProgramResult result;
  std::array<char, 4096> chunk{};
  size_t n = 0;
  while ((n = fread(chunk.data(), 1, chunk.size(), pipe)) > 0) result.output.append(chunk.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// `mpirun -np 2` as these tests start it: Open MPI refuses to run as root (CI
// does) without its two consent variables, and under ASan its own
// allocations, which are not ours, would be reported as leaks by the ranks.
inline std::string mpirun_two_ranks() {
  return "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ASAN_OPTIONS=detect_leaks=0 "
         "mpirun -np 2 --oversubscribe ";
}

inline ProgramResult run_bsg(const std::string& arguments) {
  // Appended in place: GCC 12 at -O1 warns falsely (-Warray-bounds) on
  // std::string(literal) + " " + arguments once <string> comes precompiled.
  std::string command = BSG_BINARY;
  command += ' ';
  command += arguments;
  return run_command(command);
}

// Runs bsg from the folder `cwd` with an environment changed by env(1)'s
// words in `environment` (e.g. "-u BSG_CONFIGS" or "BSG_CONFIGS=/x").
inline ProgramResult run_bsg_in(const std::string& cwd, const std::string& environment,
                                const std::string& arguments) {
  return run_command("cd '" + cwd + "' && env " + environment + " " + BSG_BINARY + " " + arguments);
}

}  // namespace bsg::testing
