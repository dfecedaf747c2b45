#include "host/gen/family.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace evms::gen {
namespace {

constexpr std::array<const char*, 7> kTypes = {"still", "translation", "rotation", "zoom", "6dof", "shake", "crossing"};

struct SensorChoice {
  int width, height;
  double duration_s;  // shorter on larger sensors, so that every member has a similar event count
};
constexpr std::array<SensorChoice, 4> kSensors = {{{128, 128, 1.0}, {240, 180, 1.0}, {346, 260, 0.6}, {640, 480, 0.3}}};

double log_uniform(Random& rng, double lo, double hi) { return lo * std::pow(hi / lo, rng.uniform()); }

}  // namespace

std::span<const char* const> family_types() { return kTypes; }

bool is_family_type(const std::string& type) {
  for (const char* t : kTypes) {
    if (type == t) return true;
  }
  return false;
}

SceneConfig family_scene(const std::string& type, std::uint64_t seed, const FamilyPins& pins) {
  if (!is_family_type(type)) {
    throw std::invalid_argument("unknown scene type '" + type + "' (still, translation, rotation, zoom, 6dof, shake or crossing)");
  }
  // The type takes part in the draw, so that seed 5 of two types are unrelated scenes.
  std::uint64_t mix = seed * 0x9E3779B97F4A7C15ull;
  for (char c : type) mix = (mix ^ static_cast<unsigned char>(c)) * 0x100000001B3ull;
  Random rng(mix);

  SceneConfig c;
  c.seed = mix;
  const SensorChoice sensor = kSensors[rng.below(kSensors.size())];
  c.width = pins.width > 0 ? pins.width : sensor.width;
  c.height = pins.height > 0 ? pins.height : sensor.height;
  c.duration_s = sensor.duration_s;
  for (const SensorChoice& s : kSensors) {
    if (s.width == c.width && s.height == c.height) c.duration_s = s.duration_s;
  }
  c.layout = Layout::kScattered;
  c.objects = 1 + static_cast<int>(rng.below(12));
  if (pins.objects > 0) c.objects = pins.objects;
  const double size_scale = std::sqrt(c.width * c.height / (240.0 * 180.0));
  c.size_min_px = 5 * std::max(1.0, size_scale);
  c.size_max_px = 60 * size_scale;
  c.low_contrast_share = 0.25;
  c.speed = log_uniform(rng, 0.25, 4.0);
  c.noise_hz = log_uniform(rng, 0.05, 2.0);
  if (pins.noise_hz >= 0) c.noise_hz = pins.noise_hz;
  c.hot_pixels = static_cast<int>(rng.below(5));
  c.hot_pixel_hz = log_uniform(rng, 50, 500);
  c.threshold_sigma = rng.uniform(0.02, 0.06);
  c.refractory_us = static_cast<TimeUs>(log_uniform(rng, 50, 1000));
  c.mover_speed_px_s = 60 * size_scale;
  if (type == "still") {
    c.motion = Motion::kStill;
    if (pins.objects == 0) c.objects = std::max(c.objects, 2);
    c.movers = 1 + static_cast<int>(rng.below(static_cast<std::uint64_t>(std::min(4, c.objects))));
  } else if (type == "crossing") {
    c.motion = Motion::kTranslation;
    c.speed *= 0.25;  // a slow drift: the movers make the scene
    if (pins.objects == 0) c.objects = std::max(c.objects, 4);
    c.movers = std::min(c.objects, 2 + static_cast<int>(rng.below(3)));
    c.crossing = true;
  } else {
    parse_motion(type, c.motion);
  }
  return c;
}

SceneConfig paper_scene(Motion motion, std::uint64_t seed, double duration_s, double speed) {
  SceneConfig c;
  c.motion = motion;
  c.seed = seed;
  c.duration_s = duration_s;
  c.speed = speed;
  return c;
}

std::string describe(const SceneConfig& c) {
  char b[256];
  const char* layout = c.layout == Layout::kPoster ? "poster of" : "";
  std::snprintf(b, sizeof b, "%s %dx%d, %s %d shapes (%d moving%s), speed %.2fx, noise %.2f Hz, %d hot pixel%s, %.2f s", motion_name(c.motion),
                c.width, c.height, layout, c.layout == Layout::kPoster ? 9 : c.objects, c.movers, c.crossing ? ", crossing" : "", c.speed,
                c.noise_hz, c.hot_pixels, c.hot_pixels == 1 ? "" : "s", c.duration_s);
  return b;
}

}  // namespace evms::gen
