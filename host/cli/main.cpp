// evms: event-based mean-shift clustering and tracking, from files, cameras or generated
// scenes, on the golden model, the fixed-point core, the simulated RTL or an FPGA board.
#include <cstdio>

#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/read/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"evms: real-time clustering and multi-target tracking of event-camera output "
               "(Barranco, Fermuller & Ros, IROS 2018)"};
  evms::cli::set_invocation(argc, argv);
  app.require_subcommand(1);
  evms::cli::register_run(app);
  evms::cli::register_info(app);
  evms::cli::register_gen(app);
  evms::cli::register_params(app);
  evms::cli::register_sweep(app);
  evms::cli::register_eval(app);
  evms::cli::register_metrics(app);
  evms::cli::register_widths(app);
  evms::cli::register_cycles(app);
  evms::cli::register_vboard(app);
  evms::cli::register_view(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "evms: %s\n", evms::read::printable(e.what()).c_str());
    return 1;
  }
  return 0;
}
