// Runs the evms program (or any command) in a test and captures what it printed.
#pragma once

#include <string>

namespace evms::test {

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
  long max_rss_kb = 0;  // peak resident memory of the command
};

CommandResult run_command(const std::string& command);
// Path of the built evms program.
std::string evms_binary();

}  // namespace evms::test
