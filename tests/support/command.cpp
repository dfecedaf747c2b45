#include "tests/support/command.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "tests/support/encoders.h"

namespace evms::test {

namespace {
// `path`, a program the build makes; a test that needs it before it is built fails saying so.
std::string built_program(const char* path) {
  if (access(path, X_OK) != 0) throw std::runtime_error(std::string(path) + " is not built yet: build the whole tree (cmake --build build) before ctest");
  return path;
}
}  // namespace

std::string evms_binary() { return built_program(EVMS_BINARY); }
std::string scripted_usb_binary() { return built_program(EVMS_SCRIPTED_USB_BINARY); }

std::string read_file(const std::string& path) {
  std::stringstream ss;
  ss << std::ifstream(path, std::ios::binary).rdbuf();
  return ss.str();
}

::testing::AssertionResult same_text(const std::string& a, const std::string& b) {
  if (a == b) return ::testing::AssertionSuccess() << "the texts are the same " << a.size() << " bytes";
  size_t at = 0;
  while (at < a.size() && at < b.size() && a[at] == b[at]) ++at;
  const size_t line_start = at == 0 ? 0 : a.rfind('\n', at - 1) + 1;  // npos + 1 is 0
  const auto line = static_cast<long>(std::count(a.begin(), a.begin() + static_cast<long>(line_start), '\n')) + 1;
  auto line_of = [&](const std::string& s) { return s.substr(line_start, std::min<size_t>(s.find('\n', line_start) - line_start, 200)); };
  return ::testing::AssertionFailure() << "the texts (" << a.size() << " and " << b.size() << " bytes) differ from line " << line
                                       << ": \"" << line_of(a) << "\" against \"" << line_of(b) << "\"";
}

long number_after(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  if (at == std::string::npos) return -1;
  long n = 0;
  for (size_t i = at + label.size(); i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == ','); ++i) {
    if (text[i] != ',') n = n * 10 + (text[i] - '0');
  }
  return n;
}

std::string link_track_columns(const std::string& tracks_csv) {
  constexpr int kLinkColumns = 7;  // t_us,track_id,state,x,y,vx,vy
  std::istringstream in(tracks_csv);
  std::string line, out;
  while (std::getline(in, line)) {
    size_t end = 0;
    for (int comma = 0; comma < kLinkColumns && end != std::string::npos; ++comma) end = line.find(',', end + (comma > 0));
    out += (line.rfind('#', 0) == 0 ? line : line.substr(0, end)) + "\n";
  }
  return out;
}

BackgroundProcess::BackgroundProcess(const std::vector<std::string>& argv) {
  pid_ = fork();
  if (pid_ == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
}

BackgroundProcess::~BackgroundProcess() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
}

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
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

namespace {
std::vector<std::string> vboard_command(const std::string& path_file, std::vector<std::string> options) {
  std::vector<std::string> c = {evms_binary(), "vboard", "--path-file", path_file};
  c.insert(c.end(), options.begin(), options.end());
  return c;
}
}  // namespace

VirtualBoardProcess::VirtualBoardProcess(const TempDir& dir, std::vector<std::string> options)
    : path_file_(dir.path("vboard.path")), process_(vboard_command(path_file_, std::move(options))) {
  for (int i = 0; i < 200 && device_.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream f(path_file_);
    std::getline(f, device_);
  }
}

}  // namespace evms::test
