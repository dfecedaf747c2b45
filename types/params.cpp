#include "types/params.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

namespace evms {
namespace {

constexpr double kBig = 1e15;

constexpr std::array<const char*, 3> kKernelNames = {"gaussian", "flat", "epanechnikov"};
constexpr std::array<const char*, 3> kSeedingNames = {"every", "events", "grid"};
constexpr std::array<const char*, 3> kLabellingNames = {"votes", "nearest", "first"};
constexpr std::array<const char*, 2> kXyScaleNames = {"axes", "isotropic"};
constexpr std::array<const char*, 4> kMeasureNames = {"centroid", "box-centre", "polarity-midpoint", "pixel-centre"};
constexpr std::array<const char*, 3> kAssociationNames = {"kalman", "nearest-centre", "last-measurement"};

const std::array kTable = {
    ParamInfo{"filter-window-us", "us",
              "background-activity window: an event is kept when one of its 8 neighbours "
              "fired within this time; 0 turns the filter off",
              &Params::filter_window_us, 0, 1e9},
    ParamInfo{"filter-support", "neighbours", "neighbours that must have fired within the window for an event to be kept",
              &Params::filter_support, 1, 8},
    ParamInfo{"filter-warm-up-us", "us", "keep every event of the stream's first this long, while its neighbours' history "
              "is too short to judge it by; 0 = off",
              &Params::filter_warm_up_us, 0, 1e9},
    ParamInfo{"filter-noise-hz", "Hz", "when the events no neighbour supported came at this rate a pixel or more over the "
              "last 32.8 ms, the filter asks one more supporting neighbour of each event for the next 32.8 ms (a noisy "
              "sensor's background activity supports itself within a long window); 0 = off",
              &Params::filter_noise_hz, 0, 1e6},
    ParamInfo{"filter-noise-pixels", "px", "the largest sensor, in pixels, on which --filter-noise-hz holds as it is: on a "
              "larger sensor of P pixels the rate is filter-noise-hz sqrt(this / P), as the noise a kernel ball gathers grows "
              "with the pixels the ball spans and with the square of the rate that passes the filter; 0 = the same rate on "
              "every sensor",
              &Params::filter_noise_pixels, 0, 1e9},
    ParamInfo{"filter-quiet-hz", "Hz", "when the events no neighbour supported within the window came at less than this "
              "rate a pixel over the last 32.8 ms, the next 32.8 ms judge events by --filter-quiet-window-us instead (a quiet "
              "sensor's slow edges fire their neighbours far apart); 0 = off",
              &Params::filter_quiet_hz, 0, 1e6},
    ParamInfo{"filter-quiet-window-us", "us", "the filter's window in an interval that follows a quiet one (--filter-quiet-hz)",
              &Params::filter_quiet_window_us, 0, 1e9},
    ParamInfo{"filter-look-ahead-us", "us", "an event the filter dropped is kept after all when, by the time its packet "
              "closes, as many neighbours as the filter asked of it fired within this long after it (the first events of an "
              "edge have no history to be judged by); 0 = off",
              &Params::filter_look_ahead_us, 0, 1e9},
    ParamInfo{"packet-support", "neighbours", "when a packet closes, its events of which fewer than this many neighbours "
              "fired while it was open (before or after them) are noise; 0 = off",
              &Params::packet_support, 0, 8},
    ParamInfo{"packet-size", "events", "events (after the filter) per mean-shift packet",
              &Params::packet_size, 2, 4096},
    ParamInfo{"packet-max-span-us", "us",
              "close a packet early when the next event is this much newer than its first; "
              "0 = only close full packets",
              &Params::packet_max_span_us, 0, 1e12},
    ParamInfo{"packet-span-edge-px", "px",
              "with --packet-max-span-us, a packet may span up to 4 times it: as long as an edge at the 90th percentile of the "
              "previous packet's normal speeds (from the filter's time map) takes to move this many px on a 240 px wide sensor, "
              "in proportion on others, so that slow edges gather enough events; 0 = off (golden only)",
              &Params::packet_span_edge_px, 0, 1000},
    ParamInfo{"xy-scale", "", "position features: x/W and y/H (axes), or both over the larger side (isotropic)",
              &Params::xy_scale, 0, 0, {kXyScaleNames}},
    ParamInfo{"scale-xy", "1", "weight of the position dimensions",
              &Params::scale_xy, 0, 100},
    ParamInfo{"scale-p", "1", "weight of the polarity dimension; 0 switches polarity off",
              &Params::scale_p, 0, 100},
    ParamInfo{"scale-t", "1", "weight of the time dimension exp(-dt/tau); 0 switches it off",
              &Params::scale_t, 0, 100},
    ParamInfo{"tau-us", "us", "time constant of the decay exp(-dt/tau)", &Params::tau_us, 1,
              1e12},
    ParamInfo{"kernel", "", "mean-shift kernel profile: gaussian exp(-u/2), flat (1 inside the ball of radius h), "
              "epanechnikov (1 - u inside it); u = d^2/h^2",
              &Params::kernel, 0, 0, {kKernelNames}},
    ParamInfo{"seeding", "", "which points climb: every event; events (the first event no climb reached yet, "
              "until every event was reached); grid (one seed per occupied h-sized cell)",
              &Params::seeding, 0, 0, {kSeedingNames}},
    ParamInfo{"labelling", "", "with seeded climbs, an event's cluster: votes (the cluster whose climbs reached it "
              "most often), nearest (the nearest mode within label-reach, else noise) or first (the cluster of the first "
              "climb that reached it)",
              &Params::labelling, 0, 0, {kLabellingNames}},
    ParamInfo{"warm-scale", "1", "with --warm-start, a previous mode climbs with bandwidth max(h, this times its "
              "cluster's spread), so that a tracked object keeps a kernel its size; 0 = h", &Params::warm_scale, 0, 100},
    ParamInfo{"warm-max-bandwidth", "1", "the largest bandwidth --warm-scale gives a previous mode",
              &Params::warm_max_bandwidth, 0, 10},
    ParamInfo{"warm-reach", "1", "with --warm-start, the events a previous mode's climb reaches (and labels) are "
              "those within max(h, this times its cluster's spread) of it, at most its ball: the ball finds the centre "
              "of a large outline and its margin takes no neighbour's events; 0 = the whole ball (golden only)",
              &Params::warm_reach, 0, 100},
    ParamInfo{"label-reach", "h", "with labelling nearest, events farther than this many bandwidths from every mode "
              "are noise", &Params::label_reach, 0.1, 100},
    ParamInfo{"warm-start", "", "with seeded climbs, the previous packet's modes seed the first climbs",
              &Params::warm_start, 0, 1},
    ParamInfo{"bandwidth", "1", "kernel bandwidth h on the normalized feature space",
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
    ParamInfo{"min-density", "1", "with seeded climbs, a mode whose ball of radius h holds fewer than this many times "
              "the events a uniform spread of the packet over the sensor would put there is noise, and so are its events; "
              "0 = off",
              &Params::min_density, 0, 1000},
    ParamInfo{"density-after-links", "", "with seeded climbs and --min-density, test the density on each set of linked "
              "modes after the links, not on each mode before them: a set is noise when none of its modes is dense or "
              "when it holds fewer events than a dense mode's ball, so a sparse arc that touches a dense one stays in its "
              "cluster",
              &Params::density_after_links, 0, 1},
    ParamInfo{"link-px", "px", "with seeded climbs, clusters that have events within this distance of each other "
              "become one (an outline split by a small kernel joins again); 0 = off",
              &Params::link_px, 0, 100},
    ParamInfo{"link-px-width", "px",
              "the sensor width up to which link-px holds: on a sensor W px wide and wider than this, clusters link "
              "within link-px min(2, W / this), as a finer sensor spreads an outline's events over more pixels; 0 = link-px "
              "on every sensor",
              &Params::link_px_width, 0, 1e5},
    ParamInfo{"join-boxes", "", "with seeded climbs, clusters whose bounding boxes overlap become one",
              &Params::join_boxes, 0, 1},
    ParamInfo{"split-balance", "1", "with seeded climbs, a cluster whose events form two or more separate parts, each "
              "holding both polarities (|ON - OFF| below this times its events), becomes one cluster per part: two "
              "objects the warm ball held together, not the two edges of one object (golden and fixed, in steps of 1/256); 0 = off",
              &Params::split_balance, 0, 1},
    ParamInfo{"split-share", "1", "with --split-balance, the parts that count: at least this share of the cluster's "
              "events, in steps of 1/256 (the others join the nearest)", &Params::split_share, 0, 1},
    ParamInfo{"split-min-events", "events", "with --split-balance, the parts that count hold at least this many events "
              "(and min-cluster-size): a sparse part's polarities say little", &Params::split_min_events, 1, 65535},
    ParamInfo{"split-cell", "h", "with --split-balance, a part is 8-connected cells of this many bandwidths a side (at least 2 px)",
              &Params::split_cell, 0.05, 10},
    ParamInfo{"split-partial", "", "with --split-balance, each large part that holds both polarities becomes a cluster of its "
              "own even when other large parts hold one polarity, and those stay one cluster (the two edges of one outline); "
              "false: a cluster splits only when every large part holds both", &Params::split_partial, 0, 1},
    ParamInfo{"split-concentric", "", "with --split-balance, two groups of a cluster's parts stay one cluster when each "
              "group's centre lies in the middle half of the other's bounding box: the two circles of a ring, about one "
              "centre, not two objects side by side (golden and fixed)", &Params::split_concentric, 0, 1},
    ParamInfo{"motion-split", "1", "with seeded climbs, a cluster of 200 events or more whose bounding box holds the "
              "predictions of two confirmed tracks is split in two by its events' motion (the slopes of their local time "
              "surfaces) when two velocities explain them with at most this share of the residual one velocity leaves, "
              "taken in steps of 1/256: a fast object crossing a slow one (golden and the fixed-point core); 0 = off", &Params::motion_split, 0, 1},
    ParamInfo{"edge-join", "h", "with seeded climbs, a cluster of mostly ON events and a cluster of mostly OFF events "
              "whose centres lie within this many bandwidths of the sensor's larger side, each the other's nearest such and neither more than four "
              "times the other's events, become one: the leading and trailing edges of an outline too large for one "
              "ball; 0 = off", &Params::edge_join, 0, 100},
    ParamInfo{"edge-balance", "1", "with --edge-join, a cluster is mostly one polarity when |ON - OFF| is at least this "
              "times its events (in steps of 1/256)", &Params::edge_balance, 0, 1},
    ParamInfo{"edge-min-events", "events", "with --edge-join, the clusters it looks at hold at least this many events "
              "(and min-cluster-size)", &Params::edge_min_events, 1, 65535},
    ParamInfo{"max-clusters", "clusters",
              "clusters per packet; modes that would open a further one become noise",
              &Params::max_clusters, 1, 256},
    ParamInfo{"measure", "", "a cluster's position: the centroid of its events, the centre of their bounding box, "
              "the midpoint of its ON events' centroid and its OFF events' centroid (an edge that fires more events "
              "than the opposite edge then pulls no harder), or pixel-centre, the mean of the pixels its events fall on, "
              "each pixel once (an edge that fires more events on each pixel, as one moving across its normal does, "
              "then pulls no harder than one moving along it)",
              &Params::measure, 0, 0, {kMeasureNames}},
    ParamInfo{"midpoint-min-events", "events", "with --measure polarity-midpoint, the events each polarity needs; "
              "with fewer, the cluster's position is the centroid of its events",
              &Params::midpoint_min_events, 1, 65535},
    ParamInfo{"time-by-pixels", "", "with --measure pixel-centre, a cluster is timed at the mean timestamp of the events "
              "that placed its pixels (each pixel's first of the packet), not of all its events: an edge fires a burst on "
              "each pixel it crosses, and the pixel is where the edge was at the burst's first event (golden and the fixed-point core; "
              "the RTL builds: false)",
              &Params::time_by_pixels, 0, 1},
    ParamInfo{"association", "", "cluster IDs across packets: kalman (one-to-one against each track's "
              "Kalman prediction), last-measurement (one-to-one against each track's last cluster centre) or "
              "nearest-centre (the previous packet's nearest cluster, as the authors' code)",
              &Params::association, 0, 0, {kAssociationNames}},
    ParamInfo{"motion-measure", "px/s", "with --measure pixel-centre, a cluster whose box holds the prediction of a "
              "confirmed track moving at least this fast is measured from the pixels of its events whose time-surface slopes "
              "that track's velocity explains, when they are half its pixels or more: a fast object without the slow shapes "
              "it passes over (golden and the fixed-point core; other measures leave it off); 0 = off", &Params::motion_measure, 0, 1e6},
    ParamInfo{"outline-split-us", "us", "a cluster of 128 events or more whose bounding box holds the "
              "predictions of two confirmed tracks gives each event to the track whose own events of the event's polarity, "
              "over the last this long and moved on by the track's velocity, fell within 3 px of it; the cluster splits, one "
              "cluster a track that took 64 events, when the parts' motions (their time-surface slopes) differ: two objects "
              "whose outlines overlap where they cross (golden only); 0 = off", &Params::outline_split_us, 0, 1e9},
    ParamInfo{"gate-px", "px", "association gate around a track's predicted position",
              &Params::gate_px, 0, 1e6},
    ParamInfo{"gate-spread", "1", "the gate widens to this many times the cluster's spread (RMS radius of "
              "its events) when that is larger; 0 = gate-px only",
              &Params::gate_spread, 0, 100},
    ParamInfo{"gate-boxes", "", "a (track, cluster) pair beyond the gate is still a candidate, taken only after every pair "
              "within it, when the track's last cluster centre lies in the cluster's bounding box or the cluster's centre in the "
              "box of the track's last cluster (an object that merges with a neighbour, or splits from it, keeps its ID)",
              &Params::gate_boxes, 0, 1},
    ParamInfo{"size-ratio", "1", "a (track, cluster) pair whose cluster has more than this many times the events of the "
              "track's last cluster, or fewer than 1/this, is taken only after every pair within it (a faint object's track "
              "does not take a bright one passing over it); 0 = off, from 1",
              &Params::size_ratio, 0, 1e6},
    ParamInfo{"confirm-hits", "packets", "measurements before a track is confirmed",
              &Params::confirm_hits, 1, 1000},
    ParamInfo{"report-tentative", "", "tentative tracks report their updates too (state tentative in tracks.csv), so that "
              "every label is a track of tracks.csv", &Params::report_tentative, 0, 1},
    ParamInfo{"coast-us", "us", "a confirmed track ends after this long without a measurement",
              &Params::coast_us, 0, 1e12},
    ParamInfo{"coast-packets", "packets", "a confirmed track also ends after missing this many packets in a row "
              "(coasting relative to the event rate); 0 = no limit",
              &Params::coast_packets, 0, 1e6},
    ParamInfo{"evict-stale", "", "with every track slot taken, a new cluster takes the slot of the unmatched "
              "track measured longest ago",
              &Params::evict_stale, 0, 1},
    ParamInfo{"accel-psd", "px^2/s^3",
              "process noise: spectral density of the white-noise acceleration, on a sensor accel-psd-width px wide",
              &Params::accel_psd, 0, kBig},
    ParamInfo{"accel-psd-width", "px",
              "the sensor width at which accel-psd holds: on a sensor W px wide the process noise is accel-psd "
              "(W / this)^2, as a k times finer sensor sees k times faster motion; 0 = accel-psd on every sensor",
              &Params::accel_psd_width, 0, 1e5},
    ParamInfo{"meas-sigma-px", "px", "standard deviation of a centroid measurement",
              &Params::meas_sigma_px, 1e-6, 1e6},
    ParamInfo{"meas-noise-from-spread", "", "a centroid's variance is meas-sigma-px^2 (spread^2 + 1/6) / events "
              "px^2 (its events' scatter over their count, a pixel's width included) instead of meas-sigma-px^2: a "
              "large, tight cluster is trusted more than a few scattered events (not in the board builds)",
              &Params::meas_noise_from_spread, 0, 1},
    ParamInfo{"init-sigma-px", "px", "initial standard deviation of a new track's position",
              &Params::init_sigma_px, 1e-6, 1e6},
    ParamInfo{"init-sigma-vel", "px/s", "initial standard deviation of a new track's velocity",
              &Params::init_sigma_vel, 1e-6, 1e9},
    ParamInfo{"max-tracks", "tracks", "tracks held at once", &Params::max_tracks, 1, 256},
    ParamInfo{"rescue-px", "px", "an event the filter dropped takes the label of the nearest labelled event of the packet "
              "it waited in, on its own pixel or within this many px (the nearest by distance, ties in row order): an object "
              "that fires too sparsely for the filter's window keeps its events, which neither join its cluster nor move its "
              "track; 0 = off (golden and fixed)",
              &Params::rescue_px, 0, 2},
};

template <class T>
constexpr bool kIsEnum = std::is_enum_v<T>;

}  // namespace

std::span<const ParamInfo> param_table() { return kTable; }

namespace {
// Events a pixel a second over the sensor and one filter interval, rounded down, at least 1; 0 = off.
std::int64_t events_per_filter_interval(double hz, SensorSize sensor) {
  if (hz <= 0) return 0;
  const double per_interval = hz * sensor.width * sensor.height * static_cast<double>(TimeUs{1} << kFilterNoiseIntervalLog2) * 1e-6;
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(per_interval));
}

// " us" after a range of microseconds; nothing for a ratio, whose unit is "1".
std::string unit_suffix(const ParamInfo& info) {
  const std::string unit = info.unit ? info.unit : "";
  return unit.empty() || unit == "1" ? "" : " " + unit;
}
}  // namespace

std::int64_t filter_noise_count(const Params& p, SensorSize sensor) {
  const double pixels = static_cast<double>(sensor.width) * sensor.height;
  const double k = p.filter_noise_pixels > 0 && pixels > p.filter_noise_pixels ? std::sqrt(p.filter_noise_pixels / pixels) : 1.0;
  return events_per_filter_interval(p.filter_noise_hz * k, sensor);
}
std::int64_t filter_quiet_count(const Params& p, SensorSize sensor) { return events_per_filter_interval(p.filter_quiet_hz, sensor); }

double accel_psd_at(const Params& p, SensorSize sensor) {
  if (p.accel_psd_width <= 0) return p.accel_psd;
  const double k = sensor.width / p.accel_psd_width;
  return p.accel_psd * k * k;
}

double link_px_at(const Params& p, SensorSize sensor) {
  if (p.link_px_width <= 0 || sensor.width <= p.link_px_width) return p.link_px;
  return p.link_px * std::min(2.0, sensor.width / p.link_px_width);
}

FeatureSides feature_sides(const Params& p, SensorSize sensor) {
  if (p.xy_scale == XyScale::kIsotropic) {
    const double side = std::max(sensor.width, sensor.height);
    return {side, side};
  }
  return {static_cast<double>(sensor.width), static_cast<double>(sensor.height)};
}

double least_support_per_event(const Params& p, SensorSize sensor) {
  // The sensor's area on the feature plane.
  const FeatureSides side = feature_sides(p, sensor);
  const double area = p.scale_xy * sensor.width / side.x * p.scale_xy * sensor.height / side.y;
  return p.min_density * M_PI * p.bandwidth * p.bandwidth / area;
}

SplitRule split_rule(const Params& p, SensorSize sensor) {
  SplitRule rule;
  if (p.split_balance <= 0) return rule;
  // The pixels of one feature unit along x and y.
  const FeatureSides side = feature_sides(p, sensor);
  const double unit_x = side.x / p.scale_xy;
  const double unit_y = side.y / p.scale_xy;
  auto scale = [&](double unit) {
    const double side = std::max(2.0, p.split_cell * p.bandwidth * unit);
    return static_cast<std::uint32_t>(std::min(std::ldexp(1.0, kSplitCellFrac - 1), std::round(std::ldexp(1.0, kSplitCellFrac) / side)));
  };
  rule.cell_scale_x = scale(unit_x);
  rule.cell_scale_y = scale(unit_y);
  auto fraction = [](double v) { return static_cast<std::uint32_t>(std::lround(std::ldexp(v, kSplitFractionFrac))); };
  rule.balance = std::max<std::uint32_t>(1, fraction(p.split_balance));
  rule.share = fraction(p.split_share);
  rule.min_events = static_cast<std::uint32_t>(std::max(p.split_min_events, p.min_cluster_size));
  rule.partial = p.split_partial;
  rule.concentric = p.split_concentric;
  return rule;
}

std::uint32_t motion_split_gain(const Params& p) {
  if (p.motion_split <= 0) return 0;
  return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(std::ldexp(p.motion_split, kMotionGainFrac))));
}

EdgeRule edge_rule(const Params& p, SensorSize sensor) {
  EdgeRule rule;
  if (p.edge_join <= 0) return rule;
  // In pixels: edge_join bandwidths of the sensor's larger side, in 1/16 px.
  const double side = std::max(sensor.width, sensor.height) / p.scale_xy;
  rule.radius2 = static_cast<std::uint64_t>(std::llround(std::pow(16 * p.edge_join * p.bandwidth * side, 2)));
  rule.balance = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(std::ldexp(p.edge_balance, kSplitFractionFrac))));
  rule.min_events = static_cast<std::uint32_t>(std::max(p.edge_min_events, p.min_cluster_size));
  return rule;
}

const ParamInfo* find_param(const std::string& name) {
  for (const ParamInfo& info : kTable) {
    if (name == info.name) return &info;
  }
  return nullptr;
}

double param_value(const Params& p, const ParamInfo& info) {
  return std::visit([&](auto member) { return static_cast<double>(p.*member); }, info.member);
}

std::string param_text(const Params& p, const ParamInfo& info) {
  return std::visit(
      [&](auto member) -> std::string {
        using T = std::remove_cvref_t<decltype(p.*member)>;
        if constexpr (kIsEnum<T>) {
          return info.choices.names[static_cast<size_t>(p.*member)];
        } else if constexpr (std::is_same_v<T, bool>) {
          return p.*member ? "true" : "false";
        } else if constexpr (std::is_floating_point_v<T>) {
          std::ostringstream os;
          os << p.*member;
          return os.str();
        } else {
          return std::to_string(p.*member);
        }
      },
      info.member);
}

std::string set_param(Params& p, const ParamInfo& info, const std::string& text) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const std::string option = "--" + std::string(info.name);
  auto bad = [&] { return option + ": '" + text + "' is not a number"; };
  return std::visit(
      [&](auto member) -> std::string {
        using T = std::remove_reference_t<decltype(p.*member)>;
        if constexpr (kIsEnum<T>) {
          std::string known;
          for (size_t i = 0; i < info.choices.names.size(); ++i) {
            if (text == info.choices.names[i]) {
              p.*member = static_cast<T>(i);
              return {};
            }
            known += std::string(i ? ", " : "") + info.choices.names[i];
          }
          return option + ": '" + text + "' is not one of " + known;
        } else if constexpr (std::is_same_v<T, bool>) {
          if (text == "true" || text == "1" || text == "on") p.*member = true;
          else if (text == "false" || text == "0" || text == "off") p.*member = false;
          else return option + ": '" + text + "' is not true or false";
          return {};
        } else {
          T value{};
          auto [ptr, ec] = std::from_chars(first, last, value);
          if (ec != std::errc() || ptr != last) return bad();
          if constexpr (std::is_floating_point_v<T>) {
            if (!std::isfinite(value)) return bad();
          }
          if (value < info.min || value > info.max) {
            std::ostringstream os;
            os << option << ": " << text << " is outside [" << info.min << ", " << info.max << "]" << unit_suffix(info);
            return os.str();
          }
          p.*member = value;
          return {};
        }
      },
      info.member);
}

std::string validate(const Params& p) {
  for (const ParamInfo& info : kTable) {
    if (!info.choices.names.empty()) {
      if (param_value(p, info) >= static_cast<double>(info.choices.names.size())) return std::string(info.name) + " is out of range";
      continue;
    }
    double v = param_value(p, info);
    if (!(v >= info.min && v <= info.max)) {
      std::ostringstream os;
      os << info.name << " = " << v << " is outside [" << info.min << ", " << info.max << "]" << unit_suffix(info);
      return os.str();
    }
  }
  return {};
}

}  // namespace evms
