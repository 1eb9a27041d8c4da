#include "child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

extern char** environ;

namespace pt::test {

ChildProcess::ChildProcess(const std::string& exe, const std::vector<std::string>& args, const std::string& dir) {
  int fds[2];
  if (::pipe(fds) != 0) return;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  // posix_spawn_file_actions_addchdir_np: glibc 2.29+.
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(exe.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  if (posix_spawn(&pid_, exe.c_str(), &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  err_fd_ = fds[0];
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  if (err_fd_ >= 0) ::close(err_fd_);
}

void ChildProcess::drain(int timeout_ms) {
  pollfd p{err_fd_, POLLIN, 0};
  if (err_fd_ < 0 || ::poll(&p, 1, timeout_ms) <= 0) return;
  char buf[4096];
  const ssize_t n = ::read(err_fd_, buf, sizeof buf);
  if (n > 0) {
    err_.append(buf, static_cast<std::size_t>(n));
  } else {
    ::close(err_fd_);
    err_fd_ = -1;
  }
}

bool ChildProcess::wait_for_output(const std::string& needle, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (err_.find(needle) == std::string::npos) {
    if (std::chrono::steady_clock::now() > end || err_fd_ < 0) return false;
    drain(50);
  }
  return true;
}

void ChildProcess::send(int signal_number) const {
  if (pid_ > 0) ::kill(pid_, signal_number);
}

int ChildProcess::wait(double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (pid_ > 0) {
    int raw = 0;
    const pid_t r = ::waitpid(pid_, &raw, WNOHANG);
    if (r == pid_) {
      pid_ = -1;
      while (err_fd_ >= 0) drain(100);
      if (WIFEXITED(raw)) return WEXITSTATUS(raw);
      if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
      return -1;
    }
    if (std::chrono::steady_clock::now() > end) return -1;
    drain(20);
  }
  return -1;
}

}  // namespace pt::test
