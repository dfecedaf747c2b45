// The core builds evms knows by name: the host/simulation core and the two boards. Everything
// that lists the builds is made from EVMS_CORE_BUILDS: the host's --core and --build choices
// (host/backend/backend.h, registry.cpp), the RTL generator's files (host/tools/rtl_gen writes each
// build's parameters, reset values and tables into rtl/generated/, and the build list for CMake),
// and the cosimulation, which checks each RTL build against the C++ core of the same Shape.
#pragma once

#include "hls/core/shape.h"

namespace evms::hls {

// iCEBreaker (iCE40 UP5K) beside a DVS128: 128x128, the seeded path only (the default method),
// packets of 256 (a packet closes early when more than 256 filtered events wait in it, half the
// pending queue, which the board's link window of 1,024 must exceed with the intake's packet),
// 8 clusters and tracks, 16-bit timestamps (one SPRAM) and a digit-serial shared multiplier
// (4 bits a clock). On the family's 128x128 members the seeded path at packets of 256
// scores mean F 0.917 against the Gaussian path's 0.738 at the 64 it could afford
// (docs/rtl.md, "Builds"). The lane count and the feature, weight and table formats are the
// Gaussian path's, which this build does not hold.
using Ice40Shape = Shape<128, 128, 256, 1, 8, 8, 8, 16, 7, 2 * 256, 10, 15, 8, 12, 4, 64, 4, 32, 8, 0, 1>;
// Arty A7-35T beside a DAVIS240: the default board core. It holds the seeded path only (the
// default method, at about 56 cycles an event); the Gaussian path does not fit beside it.
// Packets of 512: on the 240x180 scenes with seven shapes they score 0.003-0.011 more F than
// 256, and 1,024 would take 59 of the XC7A35T's 50 block RAMs (docs/rtl.md, "Builds"). The
// pending queue holds two packets, so that the link window (2,048) exceeds it and the intake's packet.
// The iCEBreaker as it runs: its board's core cut after the climbs (rtl/core/evms_climbs_core.sv:
// Ice40Shape's filter, 128x128 with 16-bit timestamps of 128 us; packets of 1,024 events, climb
// features of kFeatFrac 6, a mode table of 64, no warm seeds), then every step after the climbs
// on the host, as the host core holds them (the dropped events' labels, the motion measure and the pixel centre's own time
// among them). This is the ice40 build's fixed core:
// `--backend fixed --core ice40`, and the board backend's rest of an iCEBreaker
// (host/backend/board_backend.cpp), which gives the same words. Its method's scores at 128x128,
// beside the whole method's and the ice40 RTL core's method's, are in docs/rtl.md ("Builds").
using Ice40ClimbsShape = Shape<128, 128, 1024, 1, 8, 128, 128, 16, 7, 4 * 1024, 6, 15, 8, 12, 64, 64, 4, 32, 8, 0, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1>;
using ArtyShape = Shape<240, 180, 512, 8, 8, 16, 16, 16, 7, 2 * 512, 11, 16, 9, 12, 64, 64, 4, 32, 8, 0, 1>;

// X(name, FixedShape, RtlShape, sensor width, sensor height, description): the fixed backend's
// Shape, the RTL's (rtl/generated/evms_cfg_<name>.*, Verilated as Vcore_<name>), and the sensor
// the build's reset registers are for.
#define EVMS_CORE_BUILDS(X)                                                                             \
  X(host, HostShape, RtlHostShape, 1280, 720, "the host core: every recording evms reads")              \
  X(arty, ArtyShape, ArtyShape, 240, 180, "Arty A7-35T beside a DAVIS240 (rtl/board/evms_arty_top.sv)") \
  X(ice40, Ice40ClimbsShape, Ice40Shape, 128, 128, "iCEBreaker (UP5K) beside a DVS128 (rtl/board/evms_icebreaker_top.sv)")

// Where a board's core stops (EVMS_BOARD_BUILDS): the whole core, or cut after the climbs, with
// the host running the rest (host/backend/board_backend.cpp).
enum class CoreCut : int { kWhole = 0, kClimbs = 1 };

// X(name, clock Hz, UART clocks a bit, link queue depth, core cut, cut shape): the board each
// board build is for (rtl/board/evms_icebreaker_top.sv, evms_arty_top.sv). rtl_gen writes
// them as the build's Board* localparams and CMake values (the virtual boards), and the host's
// board backend keeps at most the link queue's depth of events unanswered. The queue must be
// deeper than what the core can hold unlabelled, its pending queue and its intake's packet
// (checked by rtl/board/evms_board.sv and host/backend/board_backend.cpp).
// The cut shape is the core a cut core's registers are the values of (the CutCfg* of
// rtl/generated/evms_cfg_<build>.svh): a core cut after its climbs
// (rtl/core/evms_climbs_core.sv) reads them in that shape's formats, and the host completes its
// packets in that shape.
// The whole ice40 core is 5.3 times the UP5K's LUTs (docs/rtl.md, "Area"), so the iCEBreaker's
// core stops after its climbs: the board returns each event's verdict and each packet's climbs
// frame, and the host runs the rest on them (Core::process_climbed) in the build's fixed core,
// Ice40ClimbsShape, which gives the words of `--backend fixed --core ice40`. The iCEBreaker's
// PLL makes 18 MHz of its 12 MHz oscillator (rtl/board/evms_icebreaker_top.sv), so that 3 clocks
// a bit give the FT2232H's 6 Mbaud (docs/link.md); the build routes at 18 MHz (docs/rtl.md).
#define EVMS_BOARD_BUILDS(X)                         \
  X(ice40, 18000000, 3, 1024, 1, Ice40ClimbsShape)   \
  X(arty, 100000000, 50, 2048, 0, ArtyShape)

#define EVMS_CORE_BUILD_NAME(name, fixed, rtl, width, height, description) #name,
inline constexpr const char* kCoreBuildNames[] = {EVMS_CORE_BUILDS(EVMS_CORE_BUILD_NAME)};
#undef EVMS_CORE_BUILD_NAME

}  // namespace evms::hls
