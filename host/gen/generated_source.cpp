// gen://SCENE?seed=S&speed=F&duration-s=D : a generated labelled scene as an event source,
// so that every subcommand can run without a file. SCENE is translation, rotation or 6dof.
#include <charconv>

#include "host/gen/scene_generator.h"
#include "host/gen/scene_uri.h"
#include "host/read/event_source.h"
#include "host/read/uri.h"

namespace evms::gen {

SceneConfig parse_scene_uri(const std::string& uri) {
  SceneConfig cfg;
  const read::SourceUri parts = read::split_source_uri(uri);
  const std::string& scene = parts.target;
  if (!parse_motion(scene, cfg.motion)) {
    throw read::InputError(uri + ": unknown scene '" + scene + "' (translation, rotation or 6dof)");
  }
  for (const auto& [key, value] : parts.query) {
    auto number = [&](auto& out) {
      auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
      if (ec != std::errc() || p != value.data() + value.size()) {
        throw read::InputError(uri + ": '" + key + "' needs a number, got '" + value + "'");
      }
    };
    if (key == "seed") number(cfg.seed);
    else if (key == "speed") number(cfg.speed);
    else if (key == "duration-s") number(cfg.duration_s);
    else if (key == "noise-hz") number(cfg.noise_hz);
    else if (key == "width") number(cfg.width);
    else if (key == "height") number(cfg.height);
    else throw read::InputError(uri + ": unknown setting '" + key + "' (seed, speed, duration-s, noise-hz, width, height)");
  }
  if (!(cfg.speed > 0) || !(cfg.duration_s > 0) || cfg.width < 64 || cfg.height < 64 || cfg.width > 4096 || cfg.height > 4096) {
    throw read::InputError(uri + ": speed and duration-s must be positive and the sensor between 64 and 4096 px");
  }
  return cfg;
}

namespace {

class GeneratedSource final : public read::EventSource {
 public:
  explicit GeneratedSource(const std::string& uri) : generator_(parse_scene_uri(uri)) {
    info_.name = uri;
    info_.format = "generated scene";
    info_.sensor = generator_.sensor();
    info_.sensor_origin = "scene";
  }
  const read::SourceInfo& info() const override { return info_; }
  size_t read(std::span<Event> out) override {
    size_t n = 0;
    while (n < out.size()) {
      if (next_ == buffer_.size()) {
        buffer_.clear();
        truth_.clear();
        next_ = 0;
        if (!generator_.next(buffer_, truth_)) break;
        continue;
      }
      out[n++] = buffer_[next_++].event;
    }
    return n;
  }
  double progress() const override { return generator_.progress(); }

 private:
  SceneGenerator generator_;
  read::SourceInfo info_;
  std::vector<LabelledEvent> buffer_;
  std::vector<TruthSample> truth_;
  size_t next_ = 0;
};

}  // namespace
}  // namespace evms::gen

namespace evms::read {
std::unique_ptr<EventSource> open_generated_scene(const std::string& uri, const SourceOptions&) {
  return std::make_unique<gen::GeneratedSource>(uri);
}
}  // namespace evms::read
