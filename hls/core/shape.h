// The compile-time shape of a core: sizes, loop bounds and word widths. A build of the core
// (C++ model, RTL, board) is one Shape; the runtime settings are in config.h.
//
// Formats (raw integers; "frac" = fraction bits):
//   feature phi      unsigned, kFeatInt.kFeatFrac, in bandwidth units: the kernel is
//                    exp(-|phi_i - phi_j|^2), so phi = feature / (h * sqrt 2)
//   kernel weight    unsigned 1.kWeightFrac (1.0 is representable)
//   sums             products weight * phi truncated to kSumFrac fraction bits, summed exactly
//   position (track) signed, kPosFrac fraction bits, px
//   velocity (track) signed, kPosFrac fraction bits, px per tick; a tick is 2^kTickLog2 us
//   covariances      kCovFrac fraction bits
#pragma once

namespace evms::hls {

// Fraction bits of the seeded climbs' features and positions beyond kFeatFrac, and of the
// scale registers that make them (hls/cluster/seeded_climbs.h).
inline constexpr int kClimbFrac = 8;
inline constexpr int kClimbScaleFrac = 40;
// Fraction bits of a spread squared and of the registers that scale one (hls/cluster/centroid.h).
inline constexpr int kSpreadFrac = 8;
// Fraction bits of the density a mode's ball needs, in events per event of the packet
// (hls/cluster/seeded_climbs.h).
inline constexpr int kDensityFrac = 24;
// The polarity split's cell scales and fractions (hls/cluster/polarity_split.h): a cell index is
// (x * scale) >> kSplitCellFrac; balance and share carry kSplitFractionFrac fraction bits.
inline constexpr int kSplitCellFrac = 16;
inline constexpr int kSplitFractionFrac = 8;
// Fraction bits of the split by motion's gain, Config::motion_split_gain (hls/cluster/motion_split.h).
inline constexpr int kMotionGainFrac = 8;
// The edge join's size ratio (hls/cluster/edge_join.h): neither of two joined modes holds more
// than this many times the other's events.
inline constexpr int kEdgeSizeRatio = 4;

template <int MaxWidth, int MaxHeight, int PacketMax, int Lanes, int IterationsMax, int ClustersMax, int TracksMax,
          int TimestampBits = 16, int TimestampShift = 7, int PendingDepth = 4 * PacketMax, int FeatFrac = 11,
          int WeightFrac = 16, int ExpTableLog2 = 9, int PosFrac = 12, int MulDigitBits = 64, int ModesMax = 64, int LinkMax = 4,
          int GridSide = 32, int ReachMax = 8, int HasGaussianPath = 1, int HasSeededPath = 0, int HasPolaritySplit = 0,
          int HasPolarityMidpoint = 0, int HasEdgeJoin = 0, int HasSpreadNoise = 0, int HasGateBoxes = 0,
          int HasPixelCentre = 0, int HasDensityAfterLinks = 0, int HasWarmSeeds = 1, int HasRescue = 0,
          int HasMotionMeasure = 0, int HasPixelTime = 0, int HasConcentricGroups = 0>
struct Shape {
  // Sensor and memories.
  static constexpr int kMaxWidth = MaxWidth;
  static constexpr int kMaxHeight = MaxHeight;
  static constexpr int kTimestampBits = TimestampBits;    // per-pixel timestamp memory word: 16 or 32
  static constexpr int kTimestampShift = TimestampShift;  // stored time unit: 2^shift us
  // The filter's noise check counts in intervals of 2^kNoiseIntervalLog2 us (32.8 ms), the
  // method's kFilterNoiseIntervalLog2 (types/params.h; host/backend/core_config.h checks them equal).
  static constexpr int kNoiseIntervalLog2 = 15;
  // Packets.
  static constexpr int kPacketMax = PacketMax;   // N: kept events per packet (the runtime size may be smaller)
  static constexpr int kPendingDepth = PendingDepth;   // events held until their packet is labelled
  static constexpr int kLanes = Lanes;           // P: kernel evaluations per clock in the RTL
  static constexpr int kIterationsMax = IterationsMax;
  static constexpr int kClustersMax = ClustersMax;
  static constexpr int kTracksMax = TracksMax;
  static constexpr int kModesMax = ModesMax;     // seeded climbs: modes a packet can open
  static constexpr int kLinkMax = LinkMax;       // seeded climbs: the largest link distance, px
  static constexpr int kGridSide = GridSide;     // seeded climbs: cells of one bandwidth a side of the grid
  static constexpr int kReachMax = ReachMax;     // seeded climbs: the largest ball, in bandwidths
  // Which clustering paths the RTL build holds (the C++ core always has both; Config::seeded
  // chooses): the Gaussian mean shift of every event, and the seeded climbs with the flat
  // kernel, their links and warm seeds.
  static constexpr int kHasGaussianPath = HasGaussianPath;
  static constexpr int kHasSeededPath = HasSeededPath;
  static_assert(HasGaussianPath || HasSeededPath, "a core clusters by at least one path");
  // Whether the build holds the polarity split after the seeded path's links
  // (hls/cluster/polarity_split.h, rtl/cluster/evms_polarity_split.sv); a build without it runs
  // the method with --split-balance 0, and the host refuses any other setting for it.
  static constexpr int kHasPolaritySplit = HasPolaritySplit;
  // Whether the build's centroids can measure a cluster at the midpoint of its ON and OFF
  // events' centres of mass (Config::midpoint_min, hls/cluster/centroid.h,
  // rtl/cluster/evms_centroid.sv); a build without it measures by the centre of mass, and the
  // host refuses --measure polarity-midpoint for it.
  static constexpr int kHasPolarityMidpoint = HasPolarityMidpoint;
  // Whether the build joins the two edges of an outline after the polarity split
  // (hls/cluster/edge_join.h, rtl/cluster/evms_edge_join.sv); a build without it runs the method
  // with --edge-join 0, and the host refuses any other setting for it.
  static constexpr int kHasEdgeJoin = HasEdgeJoin;
  // Whether the build's centroids give each cluster its measurement variance from its spread
  // (Config::meas_from_spread, hls/track/measurement_variance.h, rtl/cluster/evms_centroid.sv);
  // a build without it gives every cluster r, and the host refuses
  // --meas-noise-from-spread true for it.
  static constexpr int kHasSpreadNoise = HasSpreadNoise;
  // Whether the build's tracker takes a pair beyond the gate by the boxes (Config::gate_boxes,
  // hls/track/tracker.h, rtl/track/evms_tracker.sv); a build without it runs the method with
  // --gate-boxes false (its board ties the register low, and synthesis removes the test), and
  // the host refuses --gate-boxes true for it.
  static constexpr int kHasGateBoxes = HasGateBoxes;
  // Whether the build can measure a cluster at the mean of its pixels, each pixel once
  // (Config::pixel_centre, hls/cluster/centroid.h, rtl/cluster/evms_centroid.sv; the pixels are
  // marked by the links, hls/cluster/link.h); a build without it measures by the centre of mass,
  // and the host refuses --measure pixel-centre for it.
  static constexpr int kHasPixelCentre = HasPixelCentre;
  // Whether the build can test the least density on each set of linked modes after the links
  // (Config::density_after_links, hls/cluster/sparse_sets.h; the controller's StDense in
  // rtl/core/evms_core.sv); a build without it tests each mode before the links, and the host
  // refuses --density-after-links true for it.
  static constexpr int kHasDensityAfterLinks = HasDensityAfterLinks;
  // Whether the build's method starts with warm seeds (Config::warm_start): a build completed
  // from a board whose core stops after its climbs (rtl/core/evms_climbs_core.sv, which has none)
  // starts without them, so that its words are the board's. Not an RTL parameter: every RTL
  // core holds them.
  static constexpr int kHasWarmSeeds = HasWarmSeeds;
  // Whether the build gives each event the filter dropped the label of the nearest labelled event
  // of its packet within Config::rescue_reach px (hls/core/core.h, a label a pixel of the sensor);
  // a build without it releases them as noise, and the host refuses --rescue-px for it. Not an RTL
  // parameter: no RTL core holds it, but a core cut after its climbs leaves the labels to the host,
  // whose completion of its packets does hold it (Ice40ClimbsShape).
  static constexpr int kHasRescue = HasRescue;
  static constexpr int kRescueMax = 2;  // the largest Config::rescue_reach, px
  // Whether the build measures a fast track's cluster from the pixels its velocity explains
  // (Config::motion_speed, hls/track/motion_measure.h: two words a pixel of the sensor and
  // polarity, and a mark a pixel); a build without it measures every cluster at its pixel centre,
  // and the host refuses --motion-measure for it. Not an RTL parameter: no RTL core holds it.
  static constexpr int kHasMotionMeasure = HasMotionMeasure;
  // The pixel centre timed at the mean timestamp of its pixels' first events
  // (Config::pixel_time, hls/cluster/centroid.h), not of all the cluster's events: the C++ builds only.
  static constexpr int kHasPixelTime = HasPixelTime;
  // Whether the build's polarity split keeps concentric groups one cluster
  // (Config::split_concentric, hls/cluster/polarity_split.h); a build without it splits them, and
  // the host refuses --split-concentric true for it. Not an RTL parameter: no RTL core holds it.
  static constexpr int kHasConcentricGroups = HasConcentricGroups;
  // Mean-shift words.
  static constexpr int kFeatInt = 5;
  static constexpr int kFeatFrac = FeatFrac;
  static constexpr int kFeatBits = kFeatInt + kFeatFrac;
  static constexpr int kWeightFrac = WeightFrac;
  static constexpr int kExpTableLog2 = ExpTableLog2;
  static constexpr int kExpInterpBits = 8;
  static constexpr int kSumFrac = 16;
  static constexpr int kRecipTableLog2 = 8;
  static constexpr int kRecipFrac = 20;
  static constexpr int kDecayFrac = 32;          // fraction bits of dt * (1 / tau)
  static constexpr int kCoordScaleFrac = 20;     // fraction bits of the x, y scale registers
  static constexpr int kClimbFrac = hls::kClimbFrac;
  static constexpr int kClimbScaleFrac = hls::kClimbScaleFrac;
  static constexpr int kSpreadFrac = hls::kSpreadFrac;
  static constexpr int kDensityFrac = hls::kDensityFrac;
  static constexpr int kSplitCellFrac = hls::kSplitCellFrac;
  static constexpr int kSplitFractionFrac = hls::kSplitFractionFrac;
  static constexpr int kEdgeSizeRatio = hls::kEdgeSizeRatio;
  // Tracker words.
  static constexpr int kPosFrac = PosFrac;
  static constexpr int kTickLog2 = 14;           // 16.384 ms
  static constexpr int kCovFrac = 16;
  static constexpr int kGainFrac = 20;
  static constexpr int kNoiseFrac = 32;          // q / 3, q / 2 and q per tick^3
  static constexpr int kMaxDtLog2 = 18;          // time steps above 2^18 us (262 ms) are clamped
  // Saturation bounds, each +-(2^n - 1): covariances (stored in kCovLog2 + 1 bits), gains and
  // the error a velocity gain multiplies, positions and velocities (32-bit words).
  static constexpr int kCovLog2 = 35;
  static constexpr int kGainLog2 = 27;
  static constexpr int kPosLog2 = 31;
  static constexpr int kGateDistLog2 = 12 + PosFrac;  // gating differences saturate at +-2^12 px
  // The measurement variance from the spread (hls/track/measurement_variance.h): the scatter
  // per event has kPerEventFrac fraction bits and is capped at 2^kPerEventLog2 - 1, so that r
  // (below 2^kCovLog2) times it fits 63 bits; a pixel's own width, 1/6 px^2, in kSpreadFrac bits.
  static constexpr int kPerEventFrac = 16;
  static constexpr int kPerEventLog2 = 28;
  static constexpr int kPixelWidth2 = ((1 << kSpreadFrac) + 3) / 6;
  static_assert(kCovLog2 + kPerEventLog2 <= 63, "r times the scatter per event fits 63 bits");
  // The RTL's shared 64-bit multiplier (features, centroids, tracking): 64 = one product a
  // clock (DSP cascades), fewer = that many bits of the multiplier a clock (iCE40 LUTs).
  static constexpr int kMulDigitBits = MulDigitBits;
};

// The Shape members the RTL takes as parameters, each X(Name): S::kName in C++, the parameter
// Name in rtl/core/evms_core.sv and rtl/board/evms_board.sv. host/tools/rtl_gen writes the
// parameter lists, their connections and every build's values from this list.
#define EVMS_SHAPE_RTL_PARAMETERS(X) \
  X(MaxWidth)                        \
  X(MaxHeight)                       \
  X(TimestampBits)                   \
  X(TimestampShift)                  \
  X(NoiseIntervalLog2)               \
  X(PacketMax)                       \
  X(PendingDepth)                    \
  X(Lanes)                           \
  X(IterationsMax)                   \
  X(ClustersMax)                     \
  X(TracksMax)                       \
  X(FeatInt)                         \
  X(FeatFrac)                        \
  X(WeightFrac)                      \
  X(ExpTableLog2)                    \
  X(ExpInterpBits)                   \
  X(SumFrac)                         \
  X(RecipTableLog2)                  \
  X(RecipFrac)                       \
  X(DecayFrac)                       \
  X(CoordScaleFrac)                  \
  X(PosFrac)                         \
  X(TickLog2)                        \
  X(CovFrac)                         \
  X(GainFrac)                        \
  X(NoiseFrac)                       \
  X(MaxDtLog2)                       \
  X(CovLog2)                         \
  X(GainLog2)                        \
  X(PosLog2)                         \
  X(GateDistLog2)                    \
  X(PerEventFrac)                    \
  X(PerEventLog2)                    \
  X(PixelWidth2)                     \
  X(MulDigitBits)                    \
  X(ModesMax)                        \
  X(LinkMax)                         \
  X(GridSide)                        \
  X(ReachMax)                        \
  X(ClimbFrac)                       \
  X(ClimbScaleFrac)                  \
  X(SpreadFrac)                      \
  X(DensityFrac)                     \
  X(SplitCellFrac)                   \
  X(SplitFractionFrac)               \
  X(EdgeSizeRatio)                   \
  X(HasGaussianPath)                 \
  X(HasSeededPath)                   \
  X(HasPolaritySplit)                \
  X(HasPolarityMidpoint)             \
  X(HasEdgeJoin)                     \
  X(HasSpreadNoise)                  \
  X(HasGateBoxes)                    \
  X(HasPixelCentre)                  \
  X(HasDensityAfterLinks)

// The default board build: a DAVIS240-class sensor, the defaults of docs/sweep.md, a 16-bit
// timestamp per pixel in 128 us units (one iCE40 SPRAM word), and eight kernel lanes: 88 of an
// XC7A35T's 90 DSP48E1 (docs/rtl.md, "Area").
using DefaultShape = Shape<240, 180, 256, 8, 8, 16, 16>;
// The host core's sizes and formats on a sensor of at most W x H with the filter's timestamps
// of TimestampBits bits in 2^TimestampShift us: the method's default packets (3,000 events),
// clusters and tracks (128 each), a pending queue deep enough that noisy recordings (a third
// noise, say) never close a packet early, as golden never does, and every step of the method.
template <int W, int H, int TimestampBits, int TimestampShift>
using HostCoreShape = Shape<W, H, 4096, 8, 8, 128, 128, TimestampBits, TimestampShift, 64 * 4096, 13, 16, 10, 12, 64, 4096, 8, 32, 8, 1, 0, 1, 1,
                            1, 1, 1, 1, 1, 1, 1, 1, 1, 1>;
// The host's fixed-point backend: room for every recording evms reads (up to 1280x720), and
// exact 32-bit microsecond timestamps per pixel (its filter decides exactly as golden's).
using HostShape = HostCoreShape<1280, 720, 32, 0>;
// The RTL's host-simulation build: HostShape's sensor, words and tables with smaller packet,
// cluster and track sizes, both clustering paths, the polarity split, the edge join, the
// measurement noise from the spread, the pixel centre and the least density on the linked sets.
// For settings within those sizes the two give the same words.
using RtlHostShape = Shape<1280, 720, 256, 8, 8, 16, 16, 32, 0, 64 * 256, 13, 16, 10, 12, 64, 64, 8, 32, 8, 1, 1, 1, 1, 1, 1, 1, 1, 1>;

}  // namespace evms::hls
