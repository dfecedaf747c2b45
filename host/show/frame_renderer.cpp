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
    it = trail.empty() ? trails_.erase(it) : std::next(it);
  }
}

void FrameRenderer::render(TimeUs now, Canvas& canvas, const std::vector<std::string>& overlay) {
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
  for (const auto& [id, trail] : trails_) {
    const Rgb c = label_colour(id);
    for (size_t i = 1; i < trail.size(); ++i) {
      if (trail[i].t > now) break;
      const double a = 0.35 + 0.65 * static_cast<double>(i) / trail.size();
      canvas.line((trail[i - 1].x + 0.5) * s, (trail[i - 1].y + 0.5) * s, (trail[i].x + 0.5) * s, (trail[i].y + 0.5) * s, c, a);
    }
    const TrackUpdate& last = trail.back();
    if (last.t > now) continue;
    const double x = (last.x + 0.5) * s, y = (last.y + 0.5) * s;
    canvas.circle(x, y, 3.0 * s, {255, 255, 255});
    canvas.line(x, y, x + last.vx * style_.arrow_s * s, y + last.vy * style_.arrow_s * s, {255, 255, 255});
    canvas.text(static_cast<int>(x) + 4 * s, static_cast<int>(y) - 4 * s, std::to_string(id), c, std::max(1, s / 2));
  }
  int line_y = 4;
  for (const std::string& line : overlay) {
    canvas.text(4, line_y, line, kText, 1);
    line_y += 10;
  }
}

}  // namespace evms::show
