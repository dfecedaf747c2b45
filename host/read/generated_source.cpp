// gen://SCENE?seed=S&speed=F&duration-s=D : a generated labelled scene as an event source,
// so that every subcommand can run without a file. SCENE is one of the paper's scenes
// (translation, rotation or 6dof: the shapes poster), or family/TYPE, a member of the scene
// family (host/gen/family.h) drawn from the seed (width, height, objects and noise-hz pin
// those draws).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "host/gen/family.h"
#include "host/gen/scene_generator.h"
#include "host/read/event_source.h"
#include "host/read/generated_source.h"
#include "host/read/uri.h"

namespace evms::read {

using gen::SceneConfig;

namespace {

// 0.01, 3600: the shortest text that reads back as the number.
std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

SceneConfig parse_scene_uri(const std::string& uri) {
  const SourceUri parts = split_source_uri(uri);
  const std::string& scene = parts.target;
  auto number = [&](const std::string& key, const std::string& value, auto& out) {
    auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
    bool finite = true;
    if constexpr (std::is_floating_point_v<std::remove_reference_t<decltype(out)>>) finite = std::isfinite(out);
    if (ec != std::errc() || p != value.data() + value.size() || !finite) {
      throw InputError(uri + ": '" + key + "' needs a number, got '" + value + "'");
    }
  };
  auto check_duration = [&](double duration_s) {
    if (!(duration_s >= gen::kSceneDurationMinS && duration_s <= gen::kSceneDurationMaxS)) {
      throw InputError(uri + ": duration-s must be from " + number_text(gen::kSceneDurationMinS) + " to " + number_text(gen::kSceneDurationMaxS));
    }
  };
  auto check_noise = [&](double noise_hz) {
    if (!(noise_hz >= 0 && noise_hz <= gen::kSceneNoiseHzMax)) throw InputError(uri + ": noise-hz must be from 0 to " + number_text(gen::kSceneNoiseHzMax));
  };
  SceneConfig cfg;
  const std::string family_prefix = "family/";
  if (scene.rfind(family_prefix, 0) == 0) {
    const std::string type = scene.substr(family_prefix.size());
    if (!gen::is_family_type(type)) {
      throw InputError(uri + ": unknown scene type '" + type + "' (still, translation, rotation, zoom, 6dof, shake or crossing)");
    }
    std::uint64_t seed = 1;
    double duration_s = 0;
    gen::FamilyPins pins;
    for (const auto& [key, value] : parts.query) {
      if (key == "seed") number(key, value, seed);
      else if (key == "duration-s") number(key, value, duration_s);
      else if (key == "width") number(key, value, pins.width);
      else if (key == "height") number(key, value, pins.height);
      else if (key == "objects") number(key, value, pins.objects);
      else if (key == "noise-hz") {
        number(key, value, pins.noise_hz);
        check_noise(pins.noise_hz);
      } else throw InputError(uri + ": unknown setting '" + key + "' of a family scene (seed, duration-s, width, height, objects, noise-hz)");
    }
    if ((pins.width != 0) != (pins.height != 0) ||
        (pins.width != 0 && (pins.width < gen::kSceneSideMin || pins.height < gen::kSceneSideMin || pins.width > gen::kSceneSideMax ||
                             pins.height > gen::kSceneSideMax)) ||
        pins.objects < 0 || pins.objects > 16) {
      throw InputError(uri + ": width and height go together, between " + std::to_string(gen::kSceneSideMin) + " and " +
                       std::to_string(gen::kSceneSideMax) + " px, and objects are 1 to 16");
    }
    cfg = gen::family_scene(type, seed, pins);
    if (duration_s != 0) cfg.duration_s = duration_s;
    check_duration(cfg.duration_s);
    return cfg;
  }
  gen::Motion motion;
  if (!gen::parse_motion(scene, motion) || !(motion == gen::Motion::kTranslation || motion == gen::Motion::kRotation || motion == gen::Motion::kSixDof)) {
    throw InputError(uri + ": unknown scene '" + scene + "' (translation, rotation, 6dof, or family/TYPE)");
  }
  cfg.motion = motion;
  for (const auto& [key, value] : parts.query) {
    if (key == "seed") number(key, value, cfg.seed);
    else if (key == "speed") number(key, value, cfg.speed);
    else if (key == "duration-s") number(key, value, cfg.duration_s);
    else if (key == "noise-hz") number(key, value, cfg.noise_hz);
    else if (key == "width") number(key, value, cfg.width);
    else if (key == "height") number(key, value, cfg.height);
    else if (key == "movers") number(key, value, cfg.movers);
    else throw InputError(uri + ": unknown setting '" + key + "' (seed, speed, duration-s, noise-hz, width, height, movers)");
  }
  check_duration(cfg.duration_s);
  check_noise(cfg.noise_hz);
  if (!(cfg.speed >= gen::kSceneSpeedMin && cfg.speed <= gen::kSceneSpeedMax) || cfg.width < gen::kSceneSideMin || cfg.height < gen::kSceneSideMin ||
      cfg.width > gen::kSceneSideMax || cfg.height > gen::kSceneSideMax || cfg.movers < 0 || cfg.movers > 9) {
    throw InputError(uri + ": speed must be from " + number_text(gen::kSceneSpeedMin) + " to " + number_text(gen::kSceneSpeedMax) +
                     ", the sensor between " + std::to_string(gen::kSceneSideMin) + " and " + std::to_string(gen::kSceneSideMax) +
                     " px, and movers 0 to 9");
  }
  return cfg;
}

namespace {

class GeneratedSource final : public EventSource {
 public:
  explicit GeneratedSource(const std::string& uri) : generator_(parse_scene_uri(uri)) {
    info_.name = uri;
    info_.format = "generated scene";
    info_.sensor = generator_.sensor();
    info_.sensor_origin = "scene";
  }
  const SourceInfo& info() const override { return info_; }
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
  gen::SceneGenerator generator_;
  SourceInfo info_;
  std::vector<LabelledEvent> buffer_;
  std::vector<gen::TruthSample> truth_;
  size_t next_ = 0;
};

}  // namespace

std::unique_ptr<EventSource> open_generated_scene(const std::string& uri, const SourceOptions&) {
  return std::make_unique<GeneratedSource>(uri);
}

}  // namespace evms::read
