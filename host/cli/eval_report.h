// evms eval: the paper's Table I and figures, reproduced on generated labelled scenes (and on
// the real recordings when they are present), written as DIR/report.md with SVG figures.
#pragma once

#include <string>
#include <vector>

#include "types/params.h"
#include "host/eval/chunks.h"
#include "host/eval/family_eval.h"

namespace evms::eval {

struct EvalOptions {
  std::vector<std::string> scenes = {"translation", "rotation", "6dof"};
  std::vector<double> speeds = {1, 2, 3, 4};
  std::vector<double> bandwidths = {0.04, 0.06, 0.07, 0.08, 0.09, 0.1, 0.12, 0.15};
  std::vector<std::string> backends = {"golden"};
  double duration_s = 3.0;
  std::uint64_t seed = 1;
  double tau_px = 2.5;
  std::string out;
  std::string real_dir;   // empty: no real recordings
  int jobs = 2;
  Method method;
  Chunking chunking{Chunking::Kind::kTime, 10000};
  int family_seeds = 8;   // validation members of each family type in the report
  std::vector<std::string> family_types;   // empty: every type of the family
  std::string command_line;
};

// Runs everything and writes the report; returns the path of report.md.
std::string write_report(const EvalOptions& options);

}  // namespace evms::eval
