// Running a short-lived program (sbatch, squeue) to its end and keeping what
// it printed: stdout and stderr apart, and its exit code.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace bsg::experiments {

struct CapturedOutput {
  int exit_code = -1;  // -1 if killed by a signal
  std::string out;
  std::string err;
};

// argv[0] is looked up in PATH. Throws std::runtime_error naming the program
// if it cannot be started (e.g. it is not installed).
CapturedOutput run_captured(const std::vector<std::string>& argv);

// The full path of a program found in $PATH, or nullopt.
std::optional<std::filesystem::path> find_on_path(const std::string& program);

}  // namespace bsg::experiments
