// A fixture for tests that run the tools in tools/ as processes: a temporary
// folder per test, and `run(exe, args)` with its exit status and output.
#pragma once

#include <string>

#include "scratch_dir_test.h"

namespace pt::test {

using ToolResult = CommandResult;

class ToolTest : public ScratchDirTest {
 protected:
  ToolTest() : ScratchDirTest("pt_tools_") {}

  // Runs `exe args` in the temporary folder.
  ToolResult run(const std::string& exe, const std::string& args) const { return run_command("'" + exe + "' " + args); }
};

}  // namespace pt::test
