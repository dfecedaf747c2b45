// evms view SOURCE [--backend B] : the live viewer (SDL2), or with --headless --frames DIR the
// same frames as PNG files. Keys: space pauses, + and - double or halve the replay speed,
// b switches to the next backend, q or Escape quits. With --listen there is no SOURCE: a board's
// tracks, from the events at its AER pins (docs/link.md, "Listening").

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <thread>

#include "host/backend/backend.h"
#include "host/backend/core_config.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/read/live/live_source.h"
#include "host/show/sdl_library.h"
#include "host/show/video_writer.h"
#include "host/show/view_session.h"

namespace evms::cli {
namespace {

struct ViewOptions {
  std::string source = "gen://rotation";
  std::string backend = "golden";
  std::string core = "host";
  std::string board_link = "labels";
  std::string device;
  read::SourceOptions source_options;
  Method method;
  double fps = 30;
  bool headless = false;
  int paced = -1;  // --realtime 1, --no-realtime 0, neither -1: in a window yes, headless no
  std::string frames;
  std::string video;
  std::int64_t max_frames = 0;
  double hold_s = 0;
  std::vector<int> window_at;
  int scale = 2;
  bool listen = false;
  bool source_given = false;
};

// There is no screen to show a window on.
struct NoDisplay : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class SdlWindow {
 public:
  SdlWindow(int w, int h, const std::vector<int>& at) {
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY") && !std::getenv("SDL_VIDEODRIVER")) {
      throw NoDisplay("no display to open a window on (DISPLAY and WAYLAND_DISPLAY are not set)");
    }
    if (show::sdl().Init(SDL_INIT_VIDEO) != 0) throw NoDisplay(std::string("no display to open a window on (") + show::sdl().GetError() + ")");
    // Without a display SDL falls back to drivers that draw nowhere; only a user who asks for
    // one by SDL_VIDEODRIVER gets it.
    const std::string driver = show::sdl().GetCurrentVideoDriver() ? show::sdl().GetCurrentVideoDriver() : "";
    if ((driver == "dummy" || driver == "offscreen" || driver == "evdev") && !std::getenv("SDL_VIDEODRIVER")) {
      show::sdl().Quit();
      throw NoDisplay("no display to open a window on (SDL reached none and fell back to '" + driver + "')");
    }
    const int x = at.size() == 2 ? at[0] : static_cast<int>(SDL_WINDOWPOS_CENTERED);
    const int y = at.size() == 2 ? at[1] : static_cast<int>(SDL_WINDOWPOS_CENTERED);
    window_ = show::sdl().CreateWindow("evms", x, y, w, h, SDL_WINDOW_SHOWN);
    if (!window_) throw std::runtime_error(std::string("cannot open a window: ") + show::sdl().GetError());
    renderer_ = show::sdl().CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
    texture_ = show::sdl().CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, w, h);
    if (!renderer_ || !texture_) throw std::runtime_error(std::string("cannot draw in the window: ") + show::sdl().GetError());
  }
  ~SdlWindow() {
    if (texture_) show::sdl().DestroyTexture(texture_);
    if (renderer_) show::sdl().DestroyRenderer(renderer_);
    if (window_) show::sdl().DestroyWindow(window_);
    show::sdl().Quit();
  }
  void show(const show::Canvas& c) {
    show::sdl().UpdateTexture(texture_, nullptr, c.pixels().data(), c.width() * 3);
    show::sdl().RenderClear(renderer_);
    show::sdl().RenderCopy(renderer_, texture_, nullptr, nullptr);
    show::sdl().RenderPresent(renderer_);
  }

 private:
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  SDL_Texture* texture_ = nullptr;
};

void print_summary(show::ViewSession& session) {
  const auto& l = session.latency();
  std::printf("%s: %lld events labelled%s", session.backend_name().c_str(), static_cast<long long>(session.events()),
              session.labels_on_board() ? " on the board" : "");
  if (const read::EventSource* source = session.source()) std::printf(", %lld dropped", static_cast<long long>(source->dropped()));
  if (l.count() > 0) {
    std::printf("; latency from arrival to label p50 %.0f us, p99 %.0f us, max %.0f us", l.quantile_us(0.5), l.quantile_us(0.99),
                static_cast<double>(l.max_ns()) * 1e-3);
  }
  std::printf("\n");
}

void view(const ViewOptions& o) {
  read::SourceOptions so = o.source_options;
  // A window shows a recording at its own pace unless told otherwise; headless frames are
  // computed as fast as possible (they are the same frames either way).
  so.realtime = o.paced == -1 ? !o.headless : o.paced == 1;
  backend::BackendOptions bo;
  bo.board_keeps_labels = board_keeps_labels(o.board_link, o.backend);
  // Listening, the events enter at the board's AER pins: no source, and the board's sensor.
  auto source = o.listen ? nullptr : read::open_source(o.source, so);
  const SensorSize sensor =
      o.listen ? listening_input(o.backend, o.core, bo.board_keeps_labels, o.source_given, o.source_options).sensor : source->info().sensor;
  const Params method_params = o.method.resolve(sensor);
  bo.params = backend::fit_core_build(o.backend, o.core, method_params, o.method);
  const std::string build_note = core_build_note(o.backend, o.core, method_params, bo.params);
  bo.core = o.core;
  bo.device = o.device;
  show::ViewStyle style;
  style.scale = o.scale;
  style.track_fade_us = bo.params.coast_us;  // as long as the tracker coasts a track it lost
  show::ViewSession session = o.listen ? show::ViewSession(show::ViewSession::Listening{}, sensor, o.backend, bo, o.fps, style)
                                       : show::ViewSession(std::move(source), o.backend, bo, o.fps, style);
  show::Canvas canvas = session.make_canvas();

  const bool recording = !o.frames.empty() || !o.video.empty();
  if (o.headless && !recording) throw std::invalid_argument("--headless needs --frames DIR or --video FILE");
  if (!o.frames.empty()) std::filesystem::create_directories(o.frames);
  std::optional<show::VideoWriter> video;
  if (!o.video.empty()) {
    if (const auto folder = std::filesystem::path(o.video).parent_path(); !folder.empty()) std::filesystem::create_directories(folder);
    video.emplace(o.video, canvas.width(), canvas.height(), o.fps);
  }
  const std::string destinations =
      o.frames + (!o.frames.empty() && video ? " and " : "") + (video ? o.video : "");
  const auto save_frame = [&] {
    if (video) video->write(canvas);
    if (o.frames.empty()) return;
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06lld.png", static_cast<long long>(session.frame()));
    canvas.save_png(o.frames + name);
  };
  const auto finish = [&] {
    if (video) video->close();
    if (recording) std::printf("%lld frames in %s\n", static_cast<long long>(session.frame() + 1), destinations.c_str());
  };
  // Headless, Ctrl-C (or SIGTERM) stops at the next frame: the frames so far are whole, the
  // video is closed and the summary printed. A recording cut short exits 130, as evms run does.
  const auto write_frames = [&] {
    catch_interrupts();
    bool more = true;
    while (more && !interrupted() && (o.max_frames == 0 || session.frame() + 1 < o.max_frames)) {
      more = session.advance();
      session.render(canvas);
      save_frame();
    }
    finish();
    print_summary(session);
    if (!build_note.empty()) std::printf("%s\n", build_note.c_str());
    const bool recording_cut = interrupted() && more && session.source() && !dynamic_cast<read::LiveSource*>(session.source());
    if (recording_cut) {
      std::printf("interrupted before the end of the source: the frames hold what was shown until then\n");
      std::fflush(stdout);
      throw ExitStatus{130};
    }
  };
  if (o.headless) return write_frames();

  std::optional<SdlWindow> opened;
  try {
    opened.emplace(canvas.width(), canvas.height(), o.window_at);
  } catch (const NoDisplay& e) {
    if (!recording) throw std::runtime_error(std::string(e.what()) + ": use --headless --frames DIR or --video FILE");
    std::fprintf(stderr, "evms: %s: writing the frames to %s without a window\n", e.what(), destinations.c_str());
    return write_frames();
  }
  SdlWindow& window = *opened;
  // b cycles through the backends that implement the method being shown (what each RTL build
  // lacks: rtl_unsupported, host/backend/core_config.h).
  std::vector<std::string> cycle = {"golden"};
  if (backend::core_unsupported(bo.params).empty()) cycle.push_back("fixed");
  if (backend::rtl_unsupported(bo.params, bo.core).empty()) cycle.push_back("rtl");
  auto* control = dynamic_cast<read::PlaybackControl*>(session.source());
  bool paused = false, quit = false, more = true;
  while (!quit) {
    SDL_Event ev;
    while (show::sdl().PollEvent(&ev)) {
      if (ev.type == SDL_QUIT) quit = true;
      if (ev.type != SDL_KEYDOWN) continue;
      switch (ev.key.keysym.sym) {
        case SDLK_q:
        case SDLK_ESCAPE: quit = true; break;
        case SDLK_SPACE:
          paused = !paused;
          if (control) control->set_paused(paused);
          break;
        case SDLK_PLUS:
        case SDLK_EQUALS:
        case SDLK_KP_PLUS:
          if (control) control->set_speed(control->speed() * 2);
          break;
        case SDLK_MINUS:
        case SDLK_KP_MINUS:
          if (control) control->set_speed(control->speed() / 2);
          break;
        case SDLK_b: {
          if (session.listening()) break;  // the other backends have no input of their own
          size_t i = 0;
          while (i < cycle.size() && cycle[i] != session.backend_name()) ++i;
          session.switch_backend(cycle[(i + 1) % cycle.size()]);
          break;
        }
        default: break;
      }
    }
    if (quit) break;
    if (paused || !more) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    more = session.advance();
    session.render(canvas);
    window.show(canvas);
    save_frame();
    const bool last = !more || (o.max_frames > 0 && session.frame() + 1 >= o.max_frames);
    if (last) {
      std::printf("shown frame %lld\n", static_cast<long long>(session.frame()));
      std::fflush(stdout);
      // Keep the last frame up (and the window responsive) for --hold-s, then end.
      const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.hold_s);
      while (std::chrono::steady_clock::now() < until) {
        while (show::sdl().PollEvent(&ev)) {
        }
        window.show(canvas);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      break;
    }
  }
  finish();
  print_summary(session);
  if (!build_note.empty()) std::printf("%s\n", build_note.c_str());
}

}  // namespace

namespace {

void add_view_command(CLI::App& app, const char* name, const char* help, bool live) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(name, help);
  cmd->add_option("source", o->source, "event file or URI (default: a generated rotation scene)")->default_val(o->source);
  cmd->add_option("--backend", o->backend, "implementation: golden, fixed, rtl or board (b switches among the first three that implement the method)")
      ->default_val(o->backend);
  cmd->add_option("--core", o->core, "core build of the fixed and rtl backends: host, arty or ice40")->default_val(o->core);
  cmd->add_option("--device", o->device, "serial device of the board backend; without it, the one board's UART connected (an FT2232H's channel B)");
  add_board_link_option(*cmd, o->board_link, "the events drawn grey, with the board's tracks over them");
  cmd->add_option("--fps", o->fps, "frames per second of sensor time")->default_val(o->fps)->check(finite_in(1.0, 1000.0));
  cmd->add_option("--scale", o->scale, "screen pixels per sensor pixel")->default_val(o->scale)->check(CLI::Range(1, 8));
  cmd->add_flag("--headless", o->headless, "no window: write the frames as PNG files or video (needs --frames or --video)");
  cmd->add_option("--frames", o->frames, "directory for the frames as PNG files, from the window or --headless (without a display, "
                                         "they are written headless)");
  cmd->add_option("--video", o->video, "write the frames as a video (ffmpeg; the extension picks the container: .mp4, .mkv, .webm, .gif), "
                                       "from the window or --headless, at --fps: one second of video per second of sensor time");
  cmd->add_option("--max-frames", o->max_frames, "stop after this many frames (0: at the end of the source)")->default_val(0);
  cmd->add_option("--hold-s", o->hold_s, "keep the last frame on screen this long")->default_val(0)->check(finite_in(0.0, 86400.0));
  cmd->add_option("--window-at", o->window_at, "window position X Y on the screen")->expected(2);
  if (!live) {
    cmd->add_flag_callback("--realtime", [o] { o->paced = 1; }, "show a recording at the pace of its timestamps (the default in a window)")
        ->group("Replay");
    cmd->add_flag_callback("--no-realtime", [o] { o->paced = 0; }, "show a recording as fast as it is computed (the default headless)")
        ->group("Replay");
  }
  add_source_options(*cmd, o->source_options);
  add_replay_options(*cmd, o->source_options, live ? Pacing::kAlwaysRealtime : Pacing::kChosenByCommand);
  add_method_options(*cmd, o->method);
  add_listen_option(*cmd, o->listen);
  cmd->callback([o, live, cmd] {
    ViewOptions run = *o;
    run.source_given = cmd->count("source") > 0;
    // live: a recording is replayed at its own pace even headless, so that latency means
    // what it would with a camera.
    if (live) run.paced = 1;
    view(run);
  });
}

}  // namespace

void register_view(CLI::App& app) {
  add_view_command(app, "view", "watch clusters and tracks: a window (SDL2), or PNG frames with --headless", false);
  add_view_command(app, "live", "source -> backend -> viewer in real time, measuring each event's latency from arrival to label", true);
}

}  // namespace evms::cli
