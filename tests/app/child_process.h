// Runs the pathtracer as a child process (posix_spawn) so that tests can read
// its stderr while it runs and send it signals.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace pt::test {

class ChildProcess {
 public:
  // Starts `exe args...` in `dir`; stdout goes to /dev/null, stderr to a pipe.
  ChildProcess(const std::string& exe, const std::vector<std::string>& args, const std::string& dir);
  ~ChildProcess();  // kills (SIGKILL) and reaps a child still running
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  // Reads stderr until it contains `needle` or `timeout_s` pass; true if found.
  bool wait_for_output(const std::string& needle, double timeout_s);
  void send(int signal_number) const;
  // Waits up to `timeout_s` for the exit; returns the exit status, 128 + N
  // for death by signal N, or -1 on timeout.
  int wait(double timeout_s);
  const std::string& err() const { return err_; }

 private:
  void drain(int timeout_ms);

  pid_t pid_ = -1;
  int err_fd_ = -1;
  std::string err_;
};

}  // namespace pt::test
