// The evms command line (run_evms, commands.h): event-based mean-shift clustering and tracking, from files, cameras or generated
// scenes, on the golden model, the fixed-point core, the simulated RTL or an FPGA board.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "hls/core/configs.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/read/input_error.h"

namespace {

// The number of single-character edits that turn a into b.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

template <class S>
std::string shape_text() {
  return std::to_string(S::kMaxWidth) + "x" + std::to_string(S::kMaxHeight) + ", packets of " +
         std::to_string(S::kPacketMax) + ", " + std::to_string(S::kClustersMax) + " clusters, " + std::to_string(S::kTracksMax) +
         " tracks, " + std::to_string(S::kLanes) + " lane" + (S::kLanes > 1 ? "s" : "");
}

// The nearest of `names` to `given`, a typo or two away, or "".
std::string nearest_name(const std::string& given, const std::vector<std::string>& names) {
  std::string nearest;
  size_t best = 3;
  for (const std::string& name : names) {
    const size_t d = edit_distance(given, name);
    if (d < best) best = d, nearest = name;
  }
  return nearest;
}

// A command line CLI11 refused, as one line: its reason, and for an option the subcommand does
// not know, the nearest one it does.
void print_parse_error(const CLI::App& app, const CLI::ParseError& e) {
  const CLI::App* command = nullptr;
  for (const CLI::App* sub : app.get_subcommands()) command = sub;  // the one parsed
  std::string line = e.what();
  if (command && dynamic_cast<const CLI::ExtrasError*>(&e)) {
    for (const std::string& extra : command->remaining()) {
      if (extra.rfind("--", 0) != 0) continue;
      const std::string given = extra.substr(0, extra.find('='));
      std::vector<std::string> options;
      for (const CLI::Option* o : command->get_options()) {
        for (const std::string& name : o->get_lnames()) options.push_back("--" + name);
      }
      const std::string nearest = nearest_name(given, options);
      line = "unknown option '" + given + "' for evms " + command->get_name() + (nearest.empty() ? "" : "; did you mean '" + nearest + "'?");
      break;
    }
  }
  const std::string help = command ? "evms " + command->get_name() + " --help" : "evms --help";
  std::fprintf(stderr, "evms: %s (%s lists the options)\n", evms::read::printable(line).c_str(), help.c_str());
}

void print_version() {
  std::printf("evms %s\ncore builds (fixed backend):\n", evms::cli::build_version());
#define EVMS_PRINT_BUILD(name, fixed, rtl, width, height, description) \
  std::printf("  %-5s %s\n", #name, shape_text<evms::hls::fixed>().c_str());
  EVMS_CORE_BUILDS(EVMS_PRINT_BUILD)
#undef EVMS_PRINT_BUILD
}

// "cannot create directories: No such file or directory [/x]" -> "/x: cannot create directories: ..."
std::string describe(const std::filesystem::filesystem_error& e) {
  std::string what = e.code().message();
  std::string text = e.what();
  const std::string prefix = "filesystem error: ";
  if (text.rfind(prefix, 0) == 0) text = text.substr(prefix.size());
  if (const size_t bracket = text.find(" ["); bracket != std::string::npos) text = text.substr(0, bracket);
  return e.path1().empty() ? text : e.path1().string() + ": " + text;
}

}  // namespace

int evms::cli::run_evms(int argc, char** argv) {
  CLI::App app{"evms: real-time clustering and multi-target tracking of event-camera output "
               "(Barranco, Fermuller & Ros, IROS 2018)"};
  evms::cli::set_invocation(argc, argv);
  app.require_subcommand(1);
  // Handled before parsing, which would first ask for a subcommand; listed for --help.
  app.add_flag_callback("--version", [] {}, "print the version (git describe) and the core builds, and exit");
  if (argc > 1 && std::string(argv[1]) == "--version") {
    print_version();
    return 0;
  }
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
  evms::cli::register_vectors(app);
  // A first word that is no subcommand is named, with the nearest one.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string given = argv[1];
    std::vector<std::string> commands;
    for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
    if (std::find(commands.begin(), commands.end(), given) == commands.end()) {
      const std::string nearest = nearest_name(given, commands);
      std::fprintf(stderr, "evms: unknown command '%s'%s (evms --help lists them)\n", evms::read::printable(given).c_str(),
                   nearest.empty() ? "" : ("; did you mean '" + nearest + "'?").c_str());
      return 2;
    }
  }
  // An option before the subcommand is evms's own (--help, --version) or none.
  if (argc > 1 && argv[1][0] == '-' && std::string(argv[1]) != "--help" && std::string(argv[1]) != "-h") {
    std::fprintf(stderr, "evms: unknown option '%s': options follow the command, as in 'evms run --help' (evms --help lists the commands)\n",
                 evms::read::printable(argv[1]).c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    print_parse_error(app, e);
    return 2;
  } catch (const evms::cli::ExitStatus& e) {
    return e.code;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "evms: %s\n", evms::read::printable(describe(e)).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "evms: %s\n", evms::read::printable(e.what()).c_str());
    return 1;
  }
  return 0;
}
