// A fixture for tests that run an executable as a process: a temporary folder
// per test (removed afterwards), and a shell command run in it with its exit
// status and output. The command-line tests (tests/app) and the tools' tests
// (tests/tools) build on it.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include <gtest/gtest.h>

namespace pt::test {

struct CommandResult {
  int status = -1;  // the exit status; -1 if the process did not exit normally
  std::string out, err;
};

class ScratchDirTest : public ::testing::Test {
 protected:
  // `prefix` names the temporary folders (followed by the process id and the test's name).
  explicit ScratchDirTest(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // Runs the shell command line `command` in the folder; its standard output
  // and error are captured through files that are removed again.
  CommandResult run_command(const std::string& command) const {
    const std::string cmd = "cd '" + dir_.string() + "' && " + command + " > stdout.txt 2> stderr.txt";
    const int raw = std::system(cmd.c_str());
    CommandResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(path("stdout.txt"));
    r.err = slurp(path("stderr.txt"));
    std::filesystem::remove(path("stdout.txt"));
    std::filesystem::remove(path("stderr.txt"));
    return r;
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace pt::test
