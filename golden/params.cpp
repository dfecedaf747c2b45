#include "golden/params.h"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

namespace evms {
namespace {

constexpr double kBig = 1e15;

const std::array kTable = {
    ParamInfo{"filter-window-us", "us",
              "background-activity window: an event is kept when one of its 8 neighbours "
              "fired within this time; 0 turns the filter off",
              &Params::filter_window_us, 0, 1e9},
    ParamInfo{"packet-size", "events", "events (after the filter) per mean-shift packet",
              &Params::packet_size, 2, 4096},
    ParamInfo{"packet-max-span-us", "us",
              "close a packet early when the next event is this much newer than its first; "
              "0 = only close full packets",
              &Params::packet_max_span_us, 0, 1e12},
    ParamInfo{"scale-xy", "1", "weight of the position dimensions x/W and y/H",
              &Params::scale_xy, 0, 100},
    ParamInfo{"scale-p", "1", "weight of the polarity dimension; 0 switches polarity off",
              &Params::scale_p, 0, 100},
    ParamInfo{"scale-t", "1", "weight of the time dimension exp(-dt/tau); 0 switches it off",
              &Params::scale_t, 0, 100},
    ParamInfo{"tau-us", "us", "time constant of the decay exp(-dt/tau)", &Params::tau_us, 1,
              1e12},
    ParamInfo{"bandwidth", "1", "Gaussian kernel bandwidth h on the normalized feature space",
              &Params::bandwidth, 1e-4, 10},
    ParamInfo{"max-iterations", "iterations", "mean-shift iteration cap",
              &Params::max_iterations, 1, 1000},
    ParamInfo{"tolerance", "1",
              "convergence: stop when no feature coordinate moved more than this",
              &Params::tolerance, 0, 1},
    ParamInfo{"merge-radius", "1", "modes closer than this form one cluster",
              &Params::merge_radius, 0, 10},
    ParamInfo{"min-cluster-size", "events", "clusters with fewer events become noise (-1)",
              &Params::min_cluster_size, 1, 4096},
    ParamInfo{"max-clusters", "clusters",
              "clusters per packet; modes that would open a further one become noise",
              &Params::max_clusters, 1, 256},
    ParamInfo{"gate-px", "px", "association gate around a track's predicted position",
              &Params::gate_px, 0, 1e6},
    ParamInfo{"confirm-hits", "packets", "measurements before a track is confirmed",
              &Params::confirm_hits, 1, 1000},
    ParamInfo{"coast-us", "us", "a confirmed track ends after this long without a measurement",
              &Params::coast_us, 0, 1e12},
    ParamInfo{"accel-psd", "px^2/s^3",
              "process noise: spectral density of the white-noise acceleration",
              &Params::accel_psd, 0, kBig},
    ParamInfo{"meas-sigma-px", "px", "standard deviation of a centroid measurement",
              &Params::meas_sigma_px, 1e-6, 1e6},
    ParamInfo{"init-sigma-px", "px", "initial standard deviation of a new track's position",
              &Params::init_sigma_px, 1e-6, 1e6},
    ParamInfo{"init-sigma-vel", "px/s", "initial standard deviation of a new track's velocity",
              &Params::init_sigma_vel, 1e-6, 1e9},
    ParamInfo{"max-tracks", "tracks", "tracks held at once", &Params::max_tracks, 1, 256},
};

}  // namespace

std::span<const ParamInfo> param_table() { return kTable; }

double param_value(const Params& p, const ParamInfo& info) {
  return std::visit([&](auto member) { return static_cast<double>(p.*member); }, info.member);
}

std::string set_param(Params& p, const ParamInfo& info, const std::string& text) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  auto bad = [&] { return "--" + std::string(info.name) + ": '" + text + "' is not a number"; };
  return std::visit(
      [&](auto member) -> std::string {
        using T = std::remove_reference_t<decltype(p.*member)>;
        T value{};
        auto [ptr, ec] = std::from_chars(first, last, value);
        if (ec != std::errc() || ptr != last) return bad();
        if constexpr (std::is_floating_point_v<T>) {
          if (!std::isfinite(value)) return bad();
        }
        if (value < info.min || value > info.max) {
          std::ostringstream os;
          os << "--" << info.name << ": " << text << " is outside [" << info.min << ", "
             << info.max << "] " << info.unit;
          return os.str();
        }
        p.*member = value;
        return {};
      },
      info.member);
}

std::string validate(const Params& p) {
  for (const ParamInfo& info : kTable) {
    double v = param_value(p, info);
    if (!(v >= info.min && v <= info.max)) {
      std::ostringstream os;
      os << info.name << " = " << v << " is outside [" << info.min << ", " << info.max << "] "
         << info.unit;
      return os.str();
    }
  }
  return {};
}

}  // namespace evms
