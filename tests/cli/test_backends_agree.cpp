// The backends behind the CLI produce the same files: the Verilated RTL equals the fixed-point
// core of its build, and the board backend, through the virtual board's pseudo-terminal and
// the framed UART link, equals the fixed-point core of the iCE40 build.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "tests/support/command.h"
#include "tests/support/encoders.h"

namespace evms::test {
namespace {

// Runs `evms run` on one source with one backend and returns (events.csv, tracks.csv).
std::pair<std::string, std::string> run_backend(const TempDir& dir, const std::string& name, const std::string& source,
                                                const std::string& options) {
  const std::string out = dir.path(name);
  const auto r = run_command(evms_binary() + " run \"" + source + "\" --quiet --out " + out + " " + options);
  EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
  return {read_file(out + "/events.csv"), read_file(out + "/tracks.csv")};
}

// The cores implement the method of --preset gaussian (host/backend/core_config.h).
constexpr const char* kIce40Limits = " --preset gaussian --packet-size 64 --max-clusters 8 --max-tracks 8";

TEST(BackendsAgree, RtlEqualsFixedFileForFile) {
  TempDir dir;
  const std::string scene = "gen://translation?duration-s=0.15&seed=8";
  const auto fixed = run_backend(dir, "fixed", scene, "--backend fixed --preset gaussian");
  const auto rtl = run_backend(dir, "rtl", scene, "--backend rtl --preset gaussian");
  EXPECT_GT(fixed.first.size(), 1000u);
  EXPECT_EQ(rtl.first, fixed.first) << "events.csv differs";
  EXPECT_EQ(rtl.second, fixed.second) << "tracks.csv differs";
  const std::string small = "gen://rotation?duration-s=0.1&seed=9&width=128&height=128";
  EXPECT_EQ(run_backend(dir, "rtl_ice40", small, std::string("--backend rtl --core ice40") + kIce40Limits),
            run_backend(dir, "fixed_ice40", small, std::string("--backend fixed --core ice40") + kIce40Limits));
}

TEST(BackendsAgree, ACoreBuildRefusesParametersBeyondItsLimits) {
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --core ice40 --preset gaussian --quiet");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("128x128"), std::string::npos) << r.err;
  const auto bad = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --core zynq --preset gaussian --quiet");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("unknown core build 'zynq'"), std::string::npos) << bad.err;
}

// `evms vboard` in the background, for the length of a test.
class VirtualBoardProcess {
 public:
  explicit VirtualBoardProcess(const TempDir& dir)
      : path_file_(dir.path("vboard.path")), process_({evms_binary(), "vboard", "--path-file", path_file_}) {
    for (int i = 0; i < 200 && device_.empty(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      std::ifstream f(path_file_);
      std::getline(f, device_);
    }
  }
  const std::string& device() const { return device_; }

 private:
  std::string path_file_, device_;
  BackgroundProcess process_;
};

TEST(BackendsAgree, TheBoardThroughTheVirtualBoardEqualsTheFixedCore) {
  TempDir dir;
  VirtualBoardProcess board(dir);
  ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
  const std::string scene = "gen://rotation?duration-s=0.1&seed=5&width=128&height=128";
  const auto fixed = run_backend(dir, "fixed", scene, std::string("--backend fixed --core ice40") + kIce40Limits);
  const auto on_board = run_backend(dir, "board", scene, "--backend board --device " + board.device() + kIce40Limits);
  EXPECT_GT(fixed.first.size(), 1000u);
  EXPECT_EQ(on_board.first, fixed.first) << "events.csv differs";
  EXPECT_EQ(on_board.second, fixed.second) << "tracks.csv differs";
  // A second run on the same board starts from the reset frame: the same files again.
  const auto again = run_backend(dir, "board2", scene, "--backend board --device " + board.device() + kIce40Limits);
  EXPECT_EQ(again, fixed);
}

TEST(BackendsAgree, TheBoardBackendNamesWhatIsWrong) {
  const auto no_device = run_command(evms_binary() + " run gen://rotation?width=128\\&height=128 --backend board --quiet" + kIce40Limits);
  EXPECT_NE(no_device.exit_code, 0);
  EXPECT_NE(no_device.err.find("--device"), std::string::npos) << no_device.err;
  const auto missing = run_command(evms_binary() + " run gen://rotation?width=128\\&height=128 --backend board --device /dev/evms-no-such-tty --quiet" +
                                   kIce40Limits);
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("/dev/evms-no-such-tty: cannot open the serial device"), std::string::npos) << missing.err;
  const auto params = run_command(evms_binary() + " run gen://rotation?width=128\\&height=128 --backend board --device /dev/null --preset gaussian --quiet");
  EXPECT_NE(params.exit_code, 0);
  EXPECT_NE(params.err.find("the board runs its build's settings"), std::string::npos) << params.err;
}

}  // namespace
}  // namespace evms::test
