// evms vboard : the virtual board. The Verilated board top of the iCE40 build (sim/), its UART
// bridged to a pseudo-terminal, so that the board backend runs end to end without hardware:
//
//   evms vboard &                      # prints the terminal's path, e.g. /dev/pts/3
//   evms run SCENE --backend board --device /dev/pts/3
//
// Bytes written to the terminal go into the board's receive line at 4 clocks a bit; bytes the
// board transmits come out of it. It runs until it is interrupted.
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "Vboard_ice40.h"
#include "host/cli/commands.h"
#include "sim/virtual_board.h"

namespace evms::cli {
namespace {

constexpr int kClocksPerBit = 4;                // as sim/CMakeLists.txt builds the board
constexpr std::uint64_t kBusyCycles = 400000;   // keep clocking this long after the last byte:
                                                // the core may still be clustering a packet

void serve(const std::string& path_file) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) {
    throw std::runtime_error(std::string("cannot create a pseudo-terminal: ") + std::strerror(errno));
  }
  const std::string path = ptsname(master);
  // Holding the terminal open keeps it usable between clients, and makes it raw before any
  // client has set it: the line discipline must not echo or translate the link's bytes.
  const int slave = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  termios t{};
  tcgetattr(slave, &t);
  cfmakeraw(&t);
  tcsetattr(slave, TCSANOW, &t);
  std::printf("%s\n", path.c_str());
  std::fflush(stdout);
  if (!path_file.empty()) {
    if (std::FILE* f = std::fopen(path_file.c_str(), "w")) std::fprintf(f, "%s\n", path.c_str()), std::fclose(f);
  }

  sim::VirtualBoard<Vboard_ice40> board(kClocksPerBit);
  std::vector<std::uint8_t> in(4096), out;
  std::uint64_t last_activity = 0;
  for (;;) {
    const bool busy = board.sending() || board.cycles() - last_activity < kBusyCycles;
    pollfd p{master, POLLIN, 0};
    if (::poll(&p, 1, busy ? 0 : 20) > 0 && (p.revents & POLLIN)) {
      const ssize_t n = ::read(master, in.data(), in.size());
      if (n > 0) {
        board.send(std::span(in.data(), static_cast<size_t>(n)));
        last_activity = board.cycles();
      }
    }
    if (!busy && !board.sending()) continue;
    board.run(4096);
    if (!board.received.empty()) {
      out.assign(board.received.begin(), board.received.end());
      board.received.clear();
      for (size_t done = 0; done < out.size();) {
        const ssize_t n = ::write(master, out.data() + done, out.size() - done);
        if (n < 0 && errno != EINTR && errno != EAGAIN) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
        if (n > 0) done += static_cast<size_t>(n);
      }
      last_activity = board.cycles();
    }
  }
}

}  // namespace

void register_vboard(CLI::App& app) {
  auto path_file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("vboard", "the virtual board: the simulated iCE40 board top behind a pseudo-terminal, for --backend board");
  cmd->add_option("--path-file", *path_file, "also write the terminal's path to this file");
  cmd->callback([path_file] { serve(*path_file); });
}

}  // namespace evms::cli
