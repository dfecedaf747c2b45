// Every tunable of the method, with its unit and default. The defaults were chosen from the
// sweep in docs/sweep.md. The table in params.cpp is the one place that names, documents and
// bounds them: the CLI builds its options from it and docs/parameters.md is generated from it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <variant>

#include "golden/event.h"

namespace evms {

struct Params {
  // --- background-activity filter -------------------------------------------------------
  TimeUs filter_window_us = 10000;  // neighbour support window; 0 turns the filter off

  // --- packets --------------------------------------------------------------------------
  int packet_size = 256;             // events (that passed the filter) per mean-shift packet
  TimeUs packet_max_span_us = 0;     // close a packet early once it spans this long; 0 = never

  // --- features [x/W, y/H, p, exp(-dt/tau)], each scaled --------------------------------
  double scale_xy = 1.0;             // weight of the two position dimensions
  double scale_p = 0.0;              // weight of polarity; 0 switches it off
  double scale_t = 1.0;              // weight of the time decay; 0 switches it off
  double tau_us = 10000.0;           // time constant of exp(-dt/tau), dt from packet's newest event

  // --- mean shift -----------------------------------------------------------------------
  double bandwidth = 0.08;           // Gaussian kernel bandwidth h on the normalized space
  int max_iterations = 8;            // iteration cap
  double tolerance = 1e-3;           // stop when no coordinate moves more than this
  double merge_radius = 0.04;        // modes closer than this are one cluster (default h/2)
  int min_cluster_size = 8;          // smaller clusters become noise
  int max_clusters = 16;             // modes beyond this many clusters become noise

  // --- tracker --------------------------------------------------------------------------
  double gate_px = 20.0;             // association gate around the predicted position
  int confirm_hits = 3;              // measurements before a track is confirmed
  TimeUs coast_us = 100000;          // a confirmed track ends after this long without a match
  double accel_psd = 1000.0;         // white-noise-acceleration spectral density, px^2/s^3
  double meas_sigma_px = 2.0;        // centroid measurement noise (R = sigma^2 I)
  double init_sigma_px = 2.0;        // initial position uncertainty (P0)
  double init_sigma_vel = 200.0;     // initial velocity uncertainty (P0), px/s
  int max_tracks = 16;               // tracks held at once

  friend bool operator==(const Params&, const Params&) = default;
};

// One row of the parameter table.
struct ParamInfo {
  const char* name;      // CLI spelling without the leading dashes
  const char* unit;
  const char* help;
  std::variant<double Params::*, int Params::*, TimeUs Params::*> member;
  double min;            // inclusive bounds checked by validate()
  double max;
};

std::span<const ParamInfo> param_table();

// Reads a parameter as a double (for reports and docs).
double param_value(const Params& p, const ParamInfo& info);
// Sets a parameter from text; returns an error message, or an empty string on success.
std::string set_param(Params& p, const ParamInfo& info, const std::string& text);
// Checks every parameter against its bounds; returns an error message or an empty string.
std::string validate(const Params& p);

}  // namespace evms
