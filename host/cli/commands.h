#pragma once

// The subcommands' units include CLI11 (host/cli/common.h); the program's main() and the test
// harnesses that call run_evms need only its name.
namespace CLI {
class App;
}

namespace evms::cli {
// A subcommand that finished its work but must end with this exit status (its outputs are
// written and its summary printed).
struct ExitStatus {
  int code;
};

// The evms program: parses the command line, runs the subcommand, and returns the exit status.
// host/cli/evms.cpp is its main(); a test harness may call it with a source of its own behind
// a seam (tests/support/evms_scripted_usb.cpp).
int run_evms(int argc, char** argv);

void register_run(CLI::App& app);
void register_info(CLI::App& app);
void register_gen(CLI::App& app);
void register_params(CLI::App& app);
void register_sweep(CLI::App& app);
void register_eval(CLI::App& app);
void register_metrics(CLI::App& app);
void register_widths(CLI::App& app);
void register_cycles(CLI::App& app);
void register_vboard(CLI::App& app);
void register_view(CLI::App& app);
}  // namespace evms::cli
