#include "tests/support/command.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "tests/support/encoders.h"

namespace evms::test {

std::string evms_binary() { return EVMS_BINARY; }

CommandResult run_command(const std::string& command) {
  TempDir dir;
  const std::string out = dir.path("out"), err = dir.path("err");
  CommandResult r;
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string full = command + " >" + out + " 2>" + err;
    execl("/bin/sh", "sh", "-c", full.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  struct rusage usage {};
  wait4(pid, &status, 0, &usage);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.max_rss_kb = usage.ru_maxrss;
  auto slurp = [](const std::string& path) {
    std::stringstream ss;
    ss << std::ifstream(path).rdbuf();
    return ss.str();
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace evms::test
