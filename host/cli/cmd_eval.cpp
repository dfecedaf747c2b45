// evms eval : the paper's Table I and figures on generated labelled scenes (and the real
// recordings when present), written as DIR/report.md.
#include <cstdio>
#include <filesystem>

#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/cli/eval_report.h"

namespace evms::cli {

void register_eval(CLI::App& app) {
  auto o = std::make_shared<eval::EvalOptions>();
  CLI::App* cmd = app.add_subcommand("eval", "reproduce the paper's Table I and figures; write DIR/report.md");
  cmd->add_option("--scenes", o->scenes, "scenes: translation, rotation, 6dof")->delimiter(',')->default_str("translation,rotation,6dof");
  cmd->add_option("--speeds", o->speeds, "speed factors")->delimiter(',')->default_str("1,2,3,4")->check(finite_in(0.01, 100.0));
  cmd->add_option("--bandwidths", o->bandwidths, "bandwidths h for the F-against-h figure")->delimiter(',')->check(finite_in(0.0001, 10.0));
  cmd->add_option("--backends", o->backends, "implementations to evaluate side by side")->delimiter(',')->default_str("golden");
  cmd->add_option("--duration-s", o->duration_s, "length of each generated scene")->default_val(o->duration_s)->check(finite_in(0.2, 600.0));
  cmd->add_option("--seed", o->seed, "scene seed")->default_val(o->seed);
  cmd->add_option_function<std::int64_t>(
         "--chunk-events", [o](std::int64_t n) { o->chunking = {eval::Chunking::Kind::kEvents, n}; },
         "score clustering per chunk of this many events (default: per 10 ms)")
      ->check(CLI::Range(2, 10000000));
  cmd->add_option("--family-seeds", o->family_seeds, "validation members of each scene family type (0: none)")
      ->default_val(o->family_seeds)->check(CLI::Range(0, 100));
  cmd->add_option("--family-types", o->family_types, "scene family types to include (default: every type)")
      ->delimiter(',')
      ->check(CLI::IsMember(std::vector<std::string>(gen::family_types().begin(), gen::family_types().end())));
  cmd->add_option("--real-dir", o->real_dir, "folder of real recordings to include (default ../shared/data/real when present)");
  cmd->add_option("--jobs", o->jobs, "threads")->default_val(o->jobs)->check(CLI::Range(1, 64));
  cmd->add_option("--out", o->out, "output directory")->required();
  add_method_options(*cmd, o->method);
  cmd->callback([o] {
    eval::EvalOptions opts = *o;
    if (opts.real_dir.empty() && std::filesystem::exists("../shared/data/real")) opts.real_dir = "../shared/data/real";
    opts.command_line = invocation();
    const std::string path = eval::write_report(opts);
    std::printf("wrote %s\n", path.c_str());
  });
}

}  // namespace evms::cli
