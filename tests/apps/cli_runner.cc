#include "tests/apps/cli_runner.h"

#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

namespace aperture::apps::testing {

CommandResult RunShellCommand(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run: " + command);
  CommandResult result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

CommandResult RunAperture(const std::string& arguments) {
  return RunShellCommand(std::string(APERTURE_BINARY) + " " + arguments);
}

ApertureProcess::ApertureProcess(const std::vector<std::string>& arguments) {
  std::vector<std::string> argv_strings{APERTURE_BINARY};
  argv_strings.insert(argv_strings.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& argument : argv_strings) argv.push_back(argument.data());
  argv.push_back(nullptr);
  pid_ = forkpty(&terminal_, nullptr, nullptr, nullptr);
  if (pid_ < 0) throw std::runtime_error("forkpty failed: cannot start " + argv_strings[0]);
  if (pid_ == 0) {
    // As started from an interactive shell: default signal actions, none blocked (a test runner
    // started in the background ignores SIGINT, and children inherit that).
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
}

ApertureProcess::~ApertureProcess() {
  if (!exited_ && pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (terminal_ >= 0) close(terminal_);
}

void ApertureProcess::ReadOutput(int timeout_ms) {
  pollfd descriptor{terminal_, POLLIN, 0};
  if (poll(&descriptor, 1, timeout_ms) <= 0) return;
  std::array<char, 4096> buffer;
  const ssize_t n = read(terminal_, buffer.data(), buffer.size());
  if (n > 0) output_.append(buffer.data(), static_cast<std::size_t>(n));
}

bool ApertureProcess::Reap(int options) {
  if (exited_) return true;
  int status = 0;
  if (waitpid(pid_, &status, options) != pid_) return false;
  exited_ = true;
  exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return true;
}

bool ApertureProcess::WaitUntil(const std::function<bool()>& condition, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    if (Reap(WNOHANG)) return condition();
    ReadOutput(20);
  }
  return false;
}

void ApertureProcess::Signal(int signal_number) {
  if (!exited_) kill(pid_, signal_number);
}

int ApertureProcess::Wait(double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!Reap(WNOHANG)) {
    if (std::chrono::steady_clock::now() >= deadline) return -1;
    ReadOutput(20);
  }
  for (std::size_t before = 0; before != output_.size();) {  // what it wrote last
    before = output_.size();
    ReadOutput(0);
  }
  return exit_code_;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read '" + path + "'");
  return nlohmann::json::parse(file);
}

std::size_t CountLines(const std::string& path) {
  std::ifstream file(path);
  std::size_t lines = 0;
  for (std::string line; std::getline(file, line);) ++lines;
  return lines;
}

TempFolder::TempFolder(const std::string& stem) {
  std::random_device device;
  const auto base = std::filesystem::temp_directory_path();
  path_ = (base / ("aperture-" + stem + "-" + std::to_string(device()))).string();
  std::filesystem::create_directories(path_);
}

TempFolder::~TempFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace aperture::apps::testing
