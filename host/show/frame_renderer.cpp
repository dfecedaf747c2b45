#include "host/show/frame_renderer.h"

#include <algorithm>
#include <cmath>

namespace evms::show {
namespace {
constexpr Rgb kBackground{18, 18, 24};
constexpr Rgb kText{235, 235, 235};

Rgb shade(Rgb c, double f) {
  auto s = [f](std::uint8_t v) { return static_cast<std::uint8_t>(std::clamp(v * f, 0.0, 255.0)); };
  return {s(c.r), s(c.g), s(c.b)};
}
}  // namespace

FrameRenderer::FrameRenderer(SensorSize sensor, ViewStyle style) : sensor_(sensor), style_(style) {}

Canvas FrameRenderer::make_canvas() const {
  return Canvas(sensor_.width * style_.scale, sensor_.height * style_.scale, kBackground);
}

void FrameRenderer::add(const LabelledEvent& e) {
  events_.push_back(e);
  latest_ = std::max(latest_, e.event.t);
}

void FrameRenderer::add(const TrackUpdate& u) {
  trails_[u.id].push_back(u);
  latest_ = std::max(latest_, u.t);
}

void FrameRenderer::prune(TimeUs now) {
  while (!events_.empty() && now - events_.front().event.t > style_.event_window_us) events_.pop_front();
  for (auto it = trails_.begin(); it != trails_.end();) {
    auto& trail = it->second;
    while (!trail.empty() && now - trail.front().t > style_.trail_us) trail.pop_front();
    const bool faded = !trail.empty() && now - trail.back().t >= style_.track_fade_us;
    it = trail.empty() || faded ? trails_.erase(it) : std::next(it);
  }
}

FrameRenderer::TracksShown FrameRenderer::render(TimeUs now, Canvas& canvas, const std::vector<std::string>& overlay) {
  prune(now);
  canvas.clear(kBackground);
  const int s = style_.scale;
  for (const LabelledEvent& e : events_) {
    if (e.event.t > now) continue;
    // Newer events are brighter; ON events lighter than OFF events of the same track.
    const double age = static_cast<double>(now - e.event.t) / static_cast<double>(std::max<TimeUs>(1, style_.event_window_us));
    const double f = (e.event.p ? 1.0 : 0.62) * (1.0 - 0.6 * age);
    canvas.fill_rect(e.event.x * s, e.event.y * s, s, s, shade(label_colour(e.label), f));
  }
  TracksShown shown_tracks;
  for (const auto& [id, trail] : trails_) {
    // The newest update at or before `now` says how long the track has gone without one.
    size_t shown = trail.size();
    while (shown > 0 && trail[shown - 1].t > now) --shown;
    if (shown == 0) continue;
    const TrackUpdate& last = trail[shown - 1];
    const double fade = 1.0 - static_cast<double>(now - last.t) / static_cast<double>(std::max<TimeUs>(1, style_.track_fade_us));
    if (fade <= 0) continue;
    const Rgb c = label_colour(id);
    if (last.state == TrackState::kTentative) {
      // Most tentative tracks are a few packets of a small cluster that never confirm: a faint
      // dot says where the tracker is looking without burying the confirmed tracks under IDs.
      ++shown_tracks.tentative;
      canvas.circle((last.x + 0.5) * s, (last.y + 0.5) * s, 1.5 * s, shade(c, 0.5 * fade));
      continue;
    }
    ++shown_tracks.confirmed;
    if (last.events > 0 && last.x_max >= last.x_min && last.y_max >= last.y_min) {
      // The box of the cluster that last measured it (a board in tracks mode sends none).
      const double x0 = last.x_min * s, y0 = last.y_min * s, x1 = (last.x_max + 1) * s - 1, y1 = (last.y_max + 1) * s - 1;
      const double a = 0.7 * fade;
      canvas.line(x0, y0, x1, y0, c, a);
      canvas.line(x1, y0, x1, y1, c, a);
      canvas.line(x1, y1, x0, y1, c, a);
      canvas.line(x0, y1, x0, y0, c, a);
    }
    for (size_t i = 1; i < shown; ++i) {
      const double a = (0.35 + 0.65 * static_cast<double>(i) / static_cast<double>(shown)) * fade;
      canvas.line((trail[i - 1].x + 0.5) * s, (trail[i - 1].y + 0.5) * s, (trail[i].x + 0.5) * s, (trail[i].y + 0.5) * s, c, a);
    }
    const double x = (last.x + 0.5) * s, y = (last.y + 0.5) * s;
    canvas.circle(x, y, 3.0 * s, shade({255, 255, 255}, fade));
    // The arrow: where the track will be in arrow_s, cut to arrow_max_px and to the frame.
    double dx = last.vx * style_.arrow_s * s, dy = last.vy * style_.arrow_s * s;
    double keep = 1.0;
    const double length = std::hypot(dx, dy), longest = style_.arrow_max_px * s;
    if (length > longest) keep = longest / length;
    const auto limit = [&keep](double from, double d, double hi) {
      if (from + keep * d > hi) keep = std::max(0.0, (hi - from) / d);
      if (from + keep * d < 0) keep = std::max(0.0, -from / d);
    };
    limit(x, dx, canvas.width() - 1.0);
    limit(y, dy, canvas.height() - 1.0);
    canvas.line(x, y, x + keep * dx, y + keep * dy, shade({255, 255, 255}, fade));
    canvas.text(static_cast<int>(x) + 4 * s, static_cast<int>(y) - 4 * s, std::to_string(id), shade(c, fade), std::max(1, s / 2));
  }
  // The overlay grows with the frame, so that it stays readable on a large sensor.
  const int text_scale = std::max(1, canvas.width() / 640);
  int line_y = 4 * text_scale;
  std::vector<std::string> lines = overlay;
  lines.push_back("tracks " + std::to_string(shown_tracks.confirmed) + " (" + std::to_string(shown_tracks.tentative) + " tentative)");
  for (const std::string& line : lines) {
    canvas.text(4 * text_scale, line_y, line, kText, text_scale);
    line_y += 10 * text_scale;
  }
  return shown_tracks;
}

}  // namespace evms::show
