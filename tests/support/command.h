// Runs the evms program (or any command) in a test and captures what it printed.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <sys/types.h>
#include <vector>

namespace evms::test {

class TempDir;  // tests/support/encoders.h

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
  long max_rss_kb = 0;  // peak resident memory of the command
};

CommandResult run_command(const std::string& command);
// Path of the built evms program.
std::string evms_binary();
// Path of evms with a scripted camera behind usb:// (evms_scripted_usb.cpp; EVMS_USB_SCRIPT names the script).
std::string scripted_usb_binary();
// A file's whole contents, bytes as they are ("" when it cannot be read).
std::string read_file(const std::string& path);
// Whether two texts (a program's output files) are equal; when they are not, the message names
// their sizes and the first line that differs instead of printing both whole.
::testing::AssertionResult same_text(const std::string& a, const std::string& b);
// The number that follows `label` in a summary's text, its digits grouped by commas
// ("events in   12,345"); -1 when the text has no `label`.
long number_after(const std::string& text, const std::string& label);
// tracks.csv text with every line cut to the columns the board link's track frames carry
// (t_us to vy; docs/link.md): the board backend writes the measurement's columns as 0.
std::string link_track_columns(const std::string& tracks_csv);

// A program running in the background for the length of a test, its output discarded;
// terminated (SIGTERM) and waited for on destruction.
class BackgroundProcess {
 public:
  explicit BackgroundProcess(const std::vector<std::string>& argv);
  ~BackgroundProcess();
  BackgroundProcess(const BackgroundProcess&) = delete;
  BackgroundProcess& operator=(const BackgroundProcess&) = delete;

 private:
  pid_t pid_ = -1;
};

// `evms vboard` in the background, for the length of a test: device() is the terminal's path
// it printed (empty when it did not start within 10 s).
class VirtualBoardProcess {
 public:
  explicit VirtualBoardProcess(const TempDir& dir, std::vector<std::string> options = {});
  const std::string& device() const { return device_; }

 private:
  std::string path_file_, device_;
  BackgroundProcess process_;
};

}  // namespace evms::test
