// The viewer: headless frames are deterministic, and the SDL window shows exactly the headless
// frame. The window test runs the viewer on a virtual X server (Xvfb), takes a screenshot of
// the screen with Xlib and compares it pixel for pixel with the PNG of the same frame.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "host/show/frame_renderer.h"
#include "tests/support/command.h"
#include "tests/support/encoders.h"

// Xlib last: its macros (None, Status, ...) clash with names in the headers above.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace evms::test {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

Image read_png(const std::string& path) {
  Image img;
  png_image p{};
  p.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&p, path.c_str())) return img;
  p.format = PNG_FORMAT_RGB;
  img.width = static_cast<int>(p.width), img.height = static_cast<int>(p.height);
  img.rgb.resize(PNG_IMAGE_SIZE(p));
  if (!png_image_finish_read(&p, nullptr, img.rgb.data(), 0, nullptr)) img = {};
  return img;
}

const char* kScene = "gen://rotation?duration-s=0.3&seed=2";

TEST(Viewer, HeadlessFramesAreDeterministic) {
  TempDir dir;
  for (const char* d : {"a", "b"}) {
    const auto r = run_command(evms_binary() + " view \"" + kScene + "\" --headless --frames " + dir.path(d) + " --max-frames 5");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string a = read_file(dir.path("a/frame_000004.png")), b = read_file(dir.path("b/frame_000004.png"));
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
  // Something was drawn: the frame is not all background.
  const Image img = read_png(dir.path("a/frame_000004.png"));
  ASSERT_EQ(img.width, 480);
  size_t lit = 0;
  for (size_t i = 0; i + 2 < img.rgb.size(); i += 3) lit += (img.rgb[i] + img.rgb[i + 1] + img.rgb[i + 2]) > 120;
  EXPECT_GT(lit, 500u);
}

// A recording shorter than the events' window (20 ms, host/show/frame_renderer.h) ends on a
// frame at its last event, which shows its events, not on one a frame period past it.
TEST(Viewer, TheLastFrameOfAShortRecordingShowsItsEvents) {
  TempDir dir;
  const auto r = run_command(evms_binary() + " view \"gen://rotation?duration-s=0.012&seed=2\" --headless --fps 30 --frames " +
                             dir.path("f"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 frames in " + dir.path("f")), std::string::npos) << r.out;
  const Image img = read_png(dir.path("f/frame_000001.png"));
  ASSERT_EQ(img.width, 480);
  // Below the overlay's lines of text: the events.
  size_t lit = 0;
  for (size_t i = static_cast<size_t>(img.width) * 3 * 70; i + 2 < img.rgb.size(); i += 3) {
    lit += (img.rgb[i] + img.rgb[i + 1] + img.rgb[i + 2]) > 120;
  }
  EXPECT_GT(lit, 1000u);  // 1,980 at the last event; 105 (the tracks alone) a frame period past it
}

TEST(Viewer, WithoutADisplayItSaysSoAndFailsOrWritesTheFrames) {
  TempDir dir;
  const std::string no_display = "env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER " + evms_binary() + " view \"" + kScene + "\"";
  const auto r = run_command(no_display + " --max-frames 3");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "evms: no display to open a window on (DISPLAY and WAYLAND_DISPLAY are not set): use --headless --frames DIR or --video FILE\n");
  EXPECT_EQ(r.out.find("shown frame"), std::string::npos) << r.out;
  // With --frames it writes them as --headless would, and says so.
  const auto f = run_command(no_display + " --no-realtime --max-frames 3 --frames " + dir.path("f"));
  EXPECT_EQ(f.exit_code, 0) << f.err;
  EXPECT_NE(f.err.find("writing the frames to " + dir.path("f") + " without a window"), std::string::npos) << f.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("f/frame_000002.png")));
}

// --video pipes the frames to ffmpeg: the file holds as many frames as were shown, of the
// canvas's size, and its frame k is the PNG frame k up to the encoder's loss.
TEST(Viewer, VideoHoldsTheFramesThePngsShow) {
  TempDir dir;
  const std::string view = evms_binary() + " view \"" + kScene + "\" --headless --max-frames 6 ";
  const auto missing = run_command("env PATH=/nonexistent " + view + "--video " + dir.path("none.mp4"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err, "evms: " + dir.path("none.mp4") + ": writing video needs ffmpeg, which is not installed (apt install ffmpeg)\n");
  if (run_command("command -v ffmpeg && command -v ffprobe").exit_code != 0) GTEST_SKIP() << "ffmpeg is not installed (apt install ffmpeg)";

  const std::string video = dir.path("sub/v.mkv");  // the folder is made as --frames makes its own
  const auto r = run_command(view + "--frames " + dir.path("png") + " --video " + video);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("6 frames in " + dir.path("png") + " and " + video), std::string::npos) << r.out;
  const auto probe = run_command("ffprobe -v error -count_frames -show_entries stream=nb_read_frames,width,height -of csv=p=0 " + video);
  EXPECT_EQ(probe.out, "480,360,6\n");
  const auto decoded = run_command("ffmpeg -v error -i " + video + " -vf 'select=eq(n\\,5)' -frames:v 1 -f rawvideo -pix_fmt rgb24 -");
  ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
  const Image last = read_png(dir.path("png/frame_000005.png")), first = read_png(dir.path("png/frame_000000.png"));
  ASSERT_EQ(decoded.out.size(), last.rgb.size());
  ASSERT_EQ(first.rgb.size(), last.rgb.size());
  // Where frames 0 and 5 differ, the decoded frame is frame 5's colour, not frame 0's.
  size_t changed = 0, like_last = 0;
  double error = 0;
  for (size_t i = 0; i < last.rgb.size(); ++i) {
    const int v = static_cast<std::uint8_t>(decoded.out[i]);
    error += std::abs(v - last.rgb[i]);
    if (std::abs(first.rgb[i] - last.rgb[i]) < 60) continue;
    ++changed;
    like_last += std::abs(v - last.rgb[i]) < std::abs(v - first.rgb[i]);
  }
  EXPECT_LT(error / static_cast<double>(last.rgb.size()), 3.0);
  EXPECT_GT(changed, 1000u);
  EXPECT_GT(like_last, changed * 9 / 10) << like_last << " of " << changed;
  // ffmpeg's own reason, in one line, when it cannot write what was asked.
  const auto bad = run_command(view + "--video " + dir.path("v.unknown-container"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err.rfind("evms: " + dir.path("v.unknown-container") + ": ", 0), 0u) << bad.err;
  EXPECT_NE(bad.err.find("(ffmpeg: "), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// The brightest pixel of a canvas region, as the sum of its channels.
int brightest(const show::Canvas& c, int x0, int y0, int x1, int y1) {
  int best = 0;
  for (int y = std::max(0, y0); y <= std::min(c.height() - 1, y1); ++y) {
    for (int x = std::max(0, x0); x <= std::min(c.width() - 1, x1); ++x) {
      const show::Rgb p = c.get(x, y);
      best = std::max(best, p.r + p.g + p.b);
    }
  }
  return best;
}

// A board in tracks mode (evms vboard --build arty, --board-link tracks: the board with the whole
// core) sends no labels: the events are drawn grey, and only the tracks (trails, markers,
// arrows) have colour.
TEST(Viewer, ABoardInTracksModeShowsGreyEventsUnderItsTracks) {
  TempDir dir;
  VirtualBoardProcess vboard(dir, {"--build", "arty"});
  const std::string& device = vboard.device();
  ASSERT_FALSE(device.empty()) << "evms vboard did not start";
  // 180 ms of a 240x180 scene, in 20 ms frames: short, because the Arty's virtual board
  // simulates every clock of its 2 Mbaud line (500 clocks a byte at 100 MHz).
  const std::string scene = "gen://rotation?duration-s=0.2&seed=5";
  struct Counts {
    size_t grey = 0, coloured = 0, white = 0;
    long labelled = -1;  // "BACKEND: N events labelled" of the summary
  };
  const auto frame = [&](const std::string& name, const std::string& options) {
    const auto r = run_command(evms_binary() + " view \"" + scene + "\" --headless --fps 50 --max-frames 9 --frames " + dir.path(name) +
                               " " + options);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const Image img = read_png(dir.path(name + "/frame_000008.png"));
    Counts c;
    if (const size_t at = r.out.find(": "); at != std::string::npos) c.labelled = std::atol(r.out.c_str() + at + 2);
    for (size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
      const int r8 = img.rgb[i], g8 = img.rgb[i + 1], b8 = img.rgb[i + 2];
      if (r8 + g8 + b8 <= 18 + 18 + 24) continue;  // the background (host/show/frame_renderer.cpp)
      if (r8 == g8 && g8 == b8) ++(r8 > 200 ? c.white : c.grey);
      else ++c.coloured;
    }
    return c;
  };
  const Counts labelled = frame("labels", "--backend fixed --core arty");
  const Counts tracks = frame("tracks", "--backend board --core arty --board-link tracks --device " + device);
  EXPECT_GT(tracks.grey, 300u) << "the events, unlabelled";
  EXPECT_GT(tracks.white, 0u) << "a track's marker";
  EXPECT_GT(labelled.coloured, 300u);
  EXPECT_LT(tracks.coloured * 2, labelled.coloured) << "only the tracks have colour";
  // The board's own label counts (its latest progress frame) stand for the events it labelled:
  // most of the fixed core's by the last frame, never more.
  EXPECT_GT(labelled.labelled, 1000);
  EXPECT_GT(tracks.labelled * 2, labelled.labelled);
  EXPECT_LE(tracks.labelled, labelled.labelled);
}

// The live demo without a sensor: the virtual board plays a DVS128 recording into its AER
// pins, and the viewer, listening, draws the board's tracks (no events reach the host).
TEST(Viewer, ListeningToABoardsAerPinsDrawsItsTracks) {
  TempDir dir;
  VirtualBoardProcess vboard(dir, {"--build", "arty", "--aer", "gen://translation?duration-s=0.1&seed=3&width=128&height=128"});
  const std::string& device = vboard.device();
  ASSERT_FALSE(device.empty()) << "evms vboard did not start";
  // 400 frames of 20 ms of wall clock: 8 s. The simulated board runs at the host's pace and its
  // first labels wait for a full packet, so a slow or busy host needs seconds for the 500 below.
  const auto r = run_command(evms_binary() + " view --listen --backend board --core arty --board-link tracks --device " + device +
                             " --headless --fps 50 --max-frames 400 --frames " + dir.path("frames"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const size_t at = r.out.find("board: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_GT(std::atol(r.out.c_str() + at + 7), 500) << "the board's count of the events it labelled: " << r.out;
  const Image img = read_png(dir.path("frames/frame_000399.png"));
  size_t white = 0, coloured = 0;
  // Below the overlay's lines of text (white too): the tracks' markers and their coloured IDs.
  for (size_t i = static_cast<size_t>(img.width) * 3 * 60; i + 2 < img.rgb.size(); i += 3) {
    const int r8 = img.rgb[i], g8 = img.rgb[i + 1], b8 = img.rgb[i + 2];
    if (r8 == g8 && g8 == b8) white += r8 > 200;
    else coloured += r8 + g8 + b8 > 18 + 18 + 24;
  }
  EXPECT_GT(white, 50u) << "the tracks' markers";
  EXPECT_GT(coloured, 20u) << "the tracks' IDs";
  // With a SOURCE, or without the board, it says so in one line.
  const auto refused = run_command(evms_binary() + " view --listen --headless --frames " + dir.path("none"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("--listen takes the board's own input"), std::string::npos) << refused.err;
}

// Ctrl-C stops headless frames at the next one: the frames written are whole, the summary is
// printed, and a recording cut short exits 130.
TEST(Viewer, CtrlCStopsHeadlessFramesWithEveryFrameWhole) {
  TempDir dir;
  const std::string frames = dir.path("frames"), log = dir.path("log");
  const auto r = run_command(evms_binary() + " view 'gen://rotation?duration-s=60' --headless --frames " + frames + " > " + log +
                             " 2>&1 & pid=$!; for i in $(seq 600); do [ -s " + frames + "/frame_000003.png ] && break; sleep 0.05; done; "
                             "sleep 0.3; kill -INT $pid; wait $pid; echo $?");
  EXPECT_EQ(r.out, "130\n") << read_file(log);
  const std::string said = read_file(log);
  EXPECT_NE(said.find("interrupted before the end of the source"), std::string::npos) << said;
  int written = 0;
  std::sscanf(said.c_str(), "%d frames in", &written);
  ASSERT_GE(written, 4) << said;
  const auto frame = [&](int k) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06d.png", k);
    return frames + name;
  };
  EXPECT_FALSE(std::filesystem::exists(frame(written))) << "no frame after the ones it counted";
  const Image last = read_png(frame(written - 1));
  EXPECT_EQ(last.width, 480) << "a whole PNG of the 240x180 scene at scale 2";
}

TEST(Viewer, EndedTracksFadeWithinTheCoastingTimeAndArrowsStayShort) {
  show::ViewStyle style;
  style.scale = 2;
  style.track_fade_us = 100000;
  show::FrameRenderer renderer({240, 180}, style);
  TrackUpdate u;
  u.t = 1000, u.id = 3, u.x = 100, u.y = 90, u.vx = 1e6, u.vy = 0;  // absurdly fast: its arrow would cross the frame
  renderer.add(u);
  show::Canvas canvas = renderer.make_canvas();
  const auto marker = [&] { return brightest(canvas, 2 * 100 - 8, 2 * 90 - 8, 2 * 100 + 8, 2 * 90 + 8); };
  renderer.render(1000, canvas);
  const int fresh = marker();
  EXPECT_GE(fresh, 3 * 250);
  // The arrow ends style.arrow_max_px (40 px) from the track: drawn at 30 px, not at 60 px.
  EXPECT_GT(brightest(canvas, 2 * 130, 2 * 90 - 1, 2 * 130 + 1, 2 * 90 + 1), 300);
  EXPECT_LT(brightest(canvas, 2 * 160, 2 * 90 - 1, 2 * 160 + 1, 2 * 90 + 1), 100);
  renderer.render(51000, canvas);
  const int half = marker();
  EXPECT_LT(half, fresh * 3 / 4);
  EXPECT_GT(half, fresh / 4);
  renderer.render(101000, canvas);
  EXPECT_LT(marker(), 100) << "an ended track is gone after the coasting time";
}

TEST(Viewer, ConfirmedTracksShowTheirBoxAndIdTentativeTracksAFaintDot) {
  show::ViewStyle style;
  style.scale = 2;
  show::FrameRenderer renderer({240, 180}, style);
  TrackUpdate confirmed;
  confirmed.t = 1000, confirmed.id = 3, confirmed.x = 60, confirmed.y = 90, confirmed.events = 200;
  confirmed.x_min = 40, confirmed.x_max = 80, confirmed.y_min = 70, confirmed.y_max = 110;
  TrackUpdate tentative = confirmed;
  tentative.id = 5, tentative.x = 180, tentative.state = TrackState::kTentative;
  tentative.x_min = 170, tentative.x_max = 190;
  // A board in tracks mode sends no box: nothing is drawn where the fields say.
  TrackUpdate boxless = confirmed;
  boxless.id = 7, boxless.x = 120, boxless.y = 40, boxless.events = 0;
  boxless.x_min = 100, boxless.x_max = 140, boxless.y_min = 20, boxless.y_max = 60;
  for (const TrackUpdate& u : {confirmed, tentative, boxless}) renderer.add(u);
  show::Canvas canvas = renderer.make_canvas();
  const auto shown = renderer.render(1000, canvas);
  EXPECT_EQ(shown.confirmed, 2);
  EXPECT_EQ(shown.tentative, 1);
  const int background = brightest(canvas, 2 * 100, 2 * 150, 2 * 110, 2 * 160);
  // The confirmed track: its box's left and bottom edges away from the marker, and its white marker.
  EXPECT_GT(brightest(canvas, 2 * 40, 2 * 90, 2 * 40, 2 * 90), background + 100);
  EXPECT_GT(brightest(canvas, 2 * 60, 2 * 111 - 1, 2 * 60, 2 * 111 - 1), background + 100);
  EXPECT_GE(brightest(canvas, 2 * 60 - 8, 2 * 90 - 8, 2 * 60 + 8, 2 * 90 + 8), 3 * 250);
  // The tentative one: a dot at half its colour, no white marker, no box, no ID beside it.
  const int dot = brightest(canvas, 2 * 180 - 4, 2 * 90 - 4, 2 * 180 + 4, 2 * 90 + 4);
  EXPECT_GT(dot, background + 40);
  EXPECT_LE(dot, 3 * 128);
  EXPECT_EQ(brightest(canvas, 2 * 170, 2 * 80, 2 * 170, 2 * 100), background) << "no box";
  EXPECT_EQ(brightest(canvas, 2 * 180 + 6, 2 * 90 - 16, 2 * 180 + 30, 2 * 90 - 4), background) << "no ID";
  // The boxless confirmed track has its marker but no box.
  EXPECT_GE(brightest(canvas, 2 * 120 - 8, 2 * 40 - 8, 2 * 120 + 8, 2 * 40 + 8), 3 * 250);
  EXPECT_EQ(brightest(canvas, 2 * 100, 2 * 30, 2 * 100, 2 * 50), background);
}

TEST(Viewer, TheOverlayGrowsWithTheSensor) {
  for (const int width : {240, 1280}) {
    show::ViewStyle style;
    style.scale = 2;
    show::FrameRenderer renderer({width, 180}, style);
    show::Canvas canvas = renderer.make_canvas();
    renderer.render(0, canvas, {"8888"});
    // The glyphs' height: rows with text in the first line's band (lines are 10 rows apart at
    // scale 1, the first starting at row 4; the renderer's count of tracks follows it).
    const int text_scale = std::max(1, canvas.width() / 640);
    int rows = 0;
    for (int y = 0; y < 12 * text_scale; ++y) rows += brightest(canvas, 0, y, 80, y) > 300;
    EXPECT_EQ(rows, 7 * text_scale) << width;
  }
}

TEST(Viewer, HeadlessNeedsAFramesDirectory) {
  const auto r = run_command(evms_binary() + " view \"" + kScene + "\" --headless");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
}

// An Xvfb server on a free display number, for the length of a test.
class VirtualDisplay {
 public:
  VirtualDisplay() {
    if (access("/usr/bin/Xvfb", X_OK) != 0) return;
    for (int n = 91; n < 120 && display_.empty(); ++n) {
      // Appended, not `":" + to_string(n)`: GCC 12 warns falsely (-Wrestrict) on that form.
      std::string name = ":";
      name += std::to_string(n);
      if (std::filesystem::exists("/tmp/.X11-unix/X" + std::to_string(n)) || std::filesystem::exists("/tmp/.X" + std::to_string(n) + "-lock")) {
        continue;
      }
      server_ = std::make_unique<BackgroundProcess>(std::vector<std::string>{"/usr/bin/Xvfb", name, "-screen", "0", "640x480x24", "-nolisten", "tcp"});
      for (int i = 0; i < 100 && display_.empty(); ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (Display* x = XOpenDisplay(name.c_str())) {
          XCloseDisplay(x);
          display_ = name;
        }
      }
    }
  }
  const std::string& name() const { return display_; }

 private:
  std::unique_ptr<BackgroundProcess> server_;
  std::string display_;
};

Image screenshot(const std::string& display, int w, int h) {
  Image img;
  Display* x = XOpenDisplay(display.c_str());
  if (!x) return img;
  XImage* shot = XGetImage(x, DefaultRootWindow(x), 0, 0, static_cast<unsigned>(w), static_cast<unsigned>(h), AllPlanes, ZPixmap);
  if (shot) {
    img.width = w, img.height = h;
    for (int y = 0; y < h; ++y) {
      for (int xx = 0; xx < w; ++xx) {
        const unsigned long p = XGetPixel(shot, xx, y);
        img.rgb.push_back(static_cast<std::uint8_t>((p & shot->red_mask) >> 16));
        img.rgb.push_back(static_cast<std::uint8_t>((p & shot->green_mask) >> 8));
        img.rgb.push_back(static_cast<std::uint8_t>(p & shot->blue_mask));
      }
    }
    XDestroyImage(shot);
  }
  XCloseDisplay(x);
  return img;
}

TEST(Viewer, TheWindowShowsTheHeadlessFrame) {
  VirtualDisplay display;
  if (display.name().empty()) GTEST_SKIP() << "Xvfb is not installed (apt install xvfb)";
  TempDir dir;
  const auto headless = run_command(evms_binary() + " view \"" + kScene + "\" --headless --frames " + dir.path("h") + " --max-frames 8");
  ASSERT_EQ(headless.exit_code, 0) << headless.err;
  const Image want = read_png(dir.path("h/frame_000007.png"));
  ASSERT_GT(want.width, 0);

  // The same frames in a window at the screen's corner; the last one stays up for 20 s.
  const std::string cmd = "DISPLAY=" + display.name() + " SDL_VIDEODRIVER=x11 " + evms_binary() + " view \"" + kScene +
                          "\" --no-realtime --max-frames 8 --hold-s 20 --window-at 0 0 2>&1";
  std::FILE* viewer = popen(cmd.c_str(), "r");
  ASSERT_NE(viewer, nullptr);
  char line[256] = {};
  std::string said;
  while (std::fgets(line, sizeof line, viewer)) {
    said += line;
    if (said.find("shown frame 7") != std::string::npos) break;
  }
  ASSERT_NE(said.find("shown frame 7"), std::string::npos) << said;
  // The frame is on screen once the X server has drawn it; poll briefly for it.
  Image got;
  for (int i = 0; i < 50; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    got = screenshot(display.name(), want.width, want.height);
    if (got.rgb == want.rgb) break;
  }
  ASSERT_EQ(got.width, want.width);
  size_t differ = 0;
  for (size_t i = 0; i < want.rgb.size(); ++i) differ += got.rgb[i] != want.rgb[i];
  EXPECT_EQ(differ, 0u) << "of " << want.rgb.size() << " colour values, " << differ << " differ between the window and the PNG";
  std::system(("pkill -f -- '--hold-s 20 --window-at 0 0' >/dev/null 2>&1"));
  pclose(viewer);
}

}  // namespace
}  // namespace evms::test
