#include "experiments/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace bsg::experiments {

pid_t start_child(const ChildCommand& command) {
  if (command.argv.empty()) throw std::invalid_argument("start_child: empty command");
  // Everything the child needs is prepared before fork: after it, the child
  // only makes async-signal-safe calls (and setenv before exec).
  std::vector<char*> argv;
  for (const std::string& word : command.argv) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  const std::string log = command.log_file.string();
  const std::string dir = command.working_dir.string();
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_fd < 0) throw std::runtime_error("cannot open log file " + log + ": " + std::strerror(errno));

  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(log_fd);
    throw std::runtime_error("cannot start " + command.argv[0] + ": fork failed: " + std::strerror(error));
  }
  if (pid == 0) {
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);  // the mask survives exec
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    if (command.inherited_fd >= 0) ::fcntl(command.inherited_fd, F_SETFD, 0);  // survives exec
    for (const auto& [name, value] : command.environment) ::setenv(name.c_str(), value.c_str(), 1);
    if (!dir.empty() && ::chdir(dir.c_str()) != 0) ::_exit(127);
    ::execvp(argv[0], argv.data());
    const char* message = "bsg sweep: cannot execute the program: ";
    [[maybe_unused]] ssize_t ignored = ::write(STDERR_FILENO, message, std::strlen(message));
    ignored = ::write(STDERR_FILENO, argv[0], std::strlen(argv[0]));
    ignored = ::write(STDERR_FILENO, "\n", 1);
    ::_exit(127);
  }
  ::close(log_fd);
  return pid;
}

std::optional<ChildExit> reap_exited_child() {
  int status = 0;
  const pid_t pid = ::waitpid(-1, &status, WNOHANG);
  if (pid <= 0) return std::nullopt;
  ChildExit exit;
  exit.pid = pid;
  if (WIFEXITED(status)) exit.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) exit.signal = WTERMSIG(status);
  return exit;
}

std::string signal_name(int signal) {
  const char* abbreviation = ::sigabbrev_np(signal);
  return abbreviation != nullptr ? std::string("SIG") + abbreviation : "signal " + std::to_string(signal);
}

std::string describe(const ChildExit& exit) {
  if (exit.signal != 0) {
    return "killed by signal " + std::to_string(exit.signal) + " (" + ::strsignal(exit.signal) + ")";
  }
  return "exit code " + std::to_string(exit.exit_code);
}

std::filesystem::path current_executable() {
  std::error_code error;
  std::filesystem::path path = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot find the bsg program (/proc/self/exe): " + error.message());
  return path;
}

std::string command_line_text(const std::vector<std::string>& argv) {
  std::string text;
  for (const std::string& word : argv) {
    if (!text.empty()) text += ' ';
    const bool plain = !word.empty() && word.find_first_not_of(
                                            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                            "0123456789_-+=.,/:@%") == std::string::npos;
    if (plain) {
      text += word;
      continue;
    }
    text += '\'';
    for (const char c : word) text += c == '\'' ? std::string("'\\''") : std::string(1, c);
    text += '\'';
  }
  return text;
}

}  // namespace bsg::experiments
