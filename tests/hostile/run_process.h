// Test-only: runs a program as a child process with a CPU-time limit and a
// memory limit, capturing its standard output and error. Used by the hostile-
// input corpus and the scaled-scene renders, which run the pathtracer
// executable the way a user would.
//
// Time: the limit is on the CPU time the child uses (RLIMIT_CPU; the kernel
// kills it with SIGXCPU, then SIGKILL), which a loaded machine does not
// stretch, unlike wall-clock time (no test may bound process wall-clock time:
// docs/testing.md). A child that blocks without using CPU (a FIFO opened for
// reading) is caught by `hang_guard_seconds` of wall-clock time, far beyond
// any run's need: a guard against hanging the suite, not a speed bound.
//
// Memory: an address-space limit (setrlimit RLIMIT_AS) in the child, so a
// file that makes the program try to allocate far too much ends in bad_alloc
// instead of exhausting the machine. Under AddressSanitizer (which reserves
// terabytes of shadow address space) the limit is given to ASan instead:
// max_allocation_size_mb makes an oversized allocation a sanitizer report.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace pt::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

struct ProcessLimits {
  double cpu_seconds = 60;               // CPU time (user + system, all threads); SIGXCPU after this
  std::size_t memory_mib = 2048;         // address space (or ASan's largest allocation); 0: none
  double hang_guard_seconds = 600;       // wall clock: the child is killed after this (a hang, not a slow run)
};

struct ProcessResult {
  bool started = false;
  bool exited = false;     // ended by exit() (not by a signal)
  int exit_code = -1;      // when exited
  int signal = 0;          // when killed by a signal
  bool timed_out = false;  // killed by us at the hang guard (blocked, e.g. on a FIFO)
  bool cpu_limit = false;  // killed by the kernel at the CPU-time limit
  double seconds = 0;
  std::string out, err;
};

inline std::string read_whole_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs argv[0] (a path) with arguments argv[1..] in directory `cwd`. stdout and
// stderr go to files in `scratch` (a directory the caller owns) and are returned.
inline ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                                 const std::filesystem::path& scratch, const ProcessLimits& limits) {
  namespace fs = std::filesystem;
  ProcessResult result;
  const fs::path out_path = scratch / "stdout.txt", err_path = scratch / "stderr.txt";
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::string asan_options;
  if (kUnderAddressSanitizer && limits.memory_mib > 0) {
    const char* inherited = std::getenv("ASAN_OPTIONS");
    asan_options = std::string(inherited ? inherited : "") + (inherited && *inherited ? ":" : "") +
                   "max_allocation_size_mb=" + std::to_string(limits.memory_mib);
  }

  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) return result;
  if (pid == 0) {
    // Child: only async-signal-safe calls until exec.
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(126);
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    if (limits.cpu_seconds > 0) {
      const rlim_t soft = static_cast<rlim_t>(limits.cpu_seconds + 0.999);
      const rlimit cpu{soft, soft + 5};  // SIGXCPU at the soft limit, SIGKILL 5 s later
      ::setrlimit(RLIMIT_CPU, &cpu);
    }
    if (limits.memory_mib > 0) {
      if (kUnderAddressSanitizer) {
        ::setenv("ASAN_OPTIONS", asan_options.c_str(), 1);
      } else {
        const rlim_t bytes = static_cast<rlim_t>(limits.memory_mib) << 20;
        const rlimit as{bytes, bytes};
        ::setrlimit(RLIMIT_AS, &as);
      }
    }
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  result.started = true;
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done < 0 || elapsed > limits.hang_guard_seconds) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      result.timed_out = done >= 0;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (WIFEXITED(status)) {
    result.exited = !result.timed_out;
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
    result.cpu_limit = !result.timed_out && (result.signal == SIGXCPU || result.signal == SIGKILL);
  }
  result.out = read_whole_file(out_path);
  result.err = read_whole_file(err_path);
  fs::remove(out_path);
  fs::remove(err_path);
  return result;
}

// Markers every sanitizer prints when it reports a problem.
inline bool has_sanitizer_report(const std::string& text) {
  for (const char* marker : {"ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:",
                             "ERROR: UndefinedBehaviorSanitizer", "WARNING: ThreadSanitizer"}) {
    if (text.find(marker) != std::string::npos) return true;
  }
  return false;
}

}  // namespace pt::test
