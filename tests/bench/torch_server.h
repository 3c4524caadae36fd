// A PyTorch comparison script of tests/bench/ run with --serve as a child process of a benchmark
// program: one request line in, one answer line out, so that the program can alternate its own
// timing rounds with PyTorch's (a virtual machine's speed drifts over minutes, so a ratio of two
// timings taken seconds apart is fairer than one of two taken a minute apart). Header-only: the
// benchmark programs are one source file each (tests/CMakeLists.txt).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace bsg::bench {

class TorchServer {
 public:
  // Runs /usr/bin/python3 `script` --serve; the script's first line is its banner, which says
  // SKIPPED where torch is missing. `program` names the benchmark in messages.
  TorchServer(const std::string& script, const std::string& program) : program_(program) {
    int to_child[2], from_child[2];
    if (pipe(to_child) != 0 || pipe(from_child) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      dup2(to_child[0], STDIN_FILENO);
      dup2(from_child[1], STDOUT_FILENO);
      close(to_child[0]), close(to_child[1]), close(from_child[0]), close(from_child[1]);
      execl("/usr/bin/python3", "python3", script.c_str(), "--serve", static_cast<char*>(nullptr));
      std::perror((program + ": cannot run /usr/bin/python3").c_str());
      _exit(127);
    }
    close(to_child[0]), close(from_child[1]);
    // A server that dies mid-run must make the next request fail with a message, not kill the
    // bench by SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    if (pid_ < 0) {
      close(to_child[1]), close(from_child[0]);
      return;
    }
    requests_ = fdopen(to_child[1], "w");
    answers_ = fdopen(from_child[0], "r");
    banner_ = read_line().value_or("  torch SKIPPED: " + script + " printed nothing");
    available_ = banner_.find("SKIPPED") == std::string::npos;
  }
  ~TorchServer() {
    if (requests_) std::fclose(requests_);  // end of input: the server exits
    if (answers_) std::fclose(answers_);
    if (pid_ > 0) waitpid(pid_, nullptr, 0);
  }
  TorchServer(const TorchServer&) = delete;
  TorchServer& operator=(const TorchServer&) = delete;

  bool available() const { return available_; }
  const std::string& banner() const { return banner_; }

  // Sends `request` (one line, no newline) and returns the answer line, or nothing (with a message
  // on stderr) if the server has gone.
  std::optional<std::string> ask(const std::string& request) {
    if (!requests_) return std::nullopt;
    std::fprintf(requests_, "%s\n", request.c_str());
    std::fflush(requests_);
    std::optional<std::string> line = read_line();
    if (!line) std::fprintf(stderr, "%s: PyTorch answered nothing to '%s'\n", program_.c_str(), request.c_str());
    return line;
  }

 private:
  std::optional<std::string> read_line() {
    if (!answers_) return std::nullopt;
    char buffer[512];
    if (!std::fgets(buffer, sizeof buffer, answers_)) return std::nullopt;
    std::string line(buffer);
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    return line;
  }

  std::string program_;
  pid_t pid_ = -1;
  FILE* requests_ = nullptr;
  FILE* answers_ = nullptr;
  std::string banner_;
  bool available_ = false;
};

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The options both comparison benchmarks take: [--torch] [--rounds R]. Returns the problem with
// `arguments` in one line, or an empty string when they parse.
struct TorchComparisonOptions {
  bool torch = false;
  int rounds = 5;
};

inline std::string parse_torch_comparison_options(int argc, char** argv, TorchComparisonOptions& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--torch") {
      options.torch = true;
    } else if (argument == "--rounds") {
      if (i + 1 >= argc) return "--rounds needs a value";
      char* end = nullptr;
      const long value = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || value < 1 || value > 1000) {
        return std::string("--rounds must be a whole number from 1 to 1000, got '") + argv[i] + "'";
      }
      options.rounds = static_cast<int>(value);
    } else {
      return "unknown argument '" + argument + "'";
    }
  }
  return "";
}

}  // namespace bsg::bench
