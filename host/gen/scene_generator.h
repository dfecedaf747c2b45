// A labelled-scene generator: flat shapes of different kinds and contrasts on a white poster,
// seen by an event camera that moves, or that stands still while some shapes move on their own.
//
// Layouts. "poster" is the Event Camera Dataset's shapes sequences: nine shapes (circle,
// ellipse, triangle, square, rectangle, pentagon, hexagon, star, diamond) on a jittered 3x3 grid
// larger than the field of view. "scattered" places `objects` shapes of any kind (the nine, and
// thin bars, concave L, cross, ring and chevron shapes) with diameters from `size_min_px` to
// `size_max_px`, some of low contrast, at random on a poster larger than the field of view.
// `movers` of the shapes move on their own, in front of the others; with `crossing` their
// paths run across other shapes (occlusions), otherwise they wander along Lissajous paths.
//
// Camera motion: still, translation, rotation (in-plane spin), zoom, 6-DoF-like (all of them),
// or hand-held shake. `speed` scales the motion's time, as the paper's speed factors did;
// sensor properties stay in real time.
//
// Sensor: each pixel compares its log intensity with the level of its last event and fires one
// event per contrast threshold crossed, at the linearly interpolated crossing time. The ON and
// OFF thresholds of every pixel are drawn once (mismatch); a pixel cannot fire again within
// the refractory period; timestamps get Gaussian jitter; background activity fires random
// pixels as a Poisson process, and hot pixels fire at their own high rates. Events are
// emitted in time order.
//
// Labels: an event is labelled with the topmost shape covering its pixel (or the shape that
// just left it); noise and hot-pixel events are labelled -1. Ground truth gives each object's
// geometric centre every millisecond while its whole outline is inside the sensor.
//
// The scene family (family.h) draws all of these settings from a seed.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "types/event.h"
#include "host/gen/random.h"

namespace evms::gen {

enum class Motion { kStill, kTranslation, kRotation, kZoom, kSixDof, kShake };
enum class Layout { kPoster, kScattered };

// The ranges a scene's settings take, from `evms gen` and from gen:// URIs alike: a scene of
// more than an hour or a rate beyond 1 kHz a pixel is a typo, and a sensor is 64 to 4096 px a side.
inline constexpr double kSceneSpeedMin = 0.01, kSceneSpeedMax = 100;
inline constexpr double kSceneDurationMinS = 0.001, kSceneDurationMaxS = 3600;
inline constexpr double kSceneNoiseHzMax = 1000;
inline constexpr int kSceneSideMin = 64, kSceneSideMax = 4096;

struct SceneConfig {
  Motion motion = Motion::kRotation;
  double speed = 1.0;              // time scale of the motion
  std::uint64_t seed = 1;
  double duration_s = 5.0;
  int width = 240, height = 180;   // DAVIS240C
  // What is in view.
  Layout layout = Layout::kPoster;
  int objects = 9;                 // scattered: how many shapes (1-16)
  double size_min_px = 5;          // scattered: shape diameters, px
  double size_max_px = 60;
  double low_contrast_share = 0;   // scattered: share of shapes only slightly darker than the poster
  int movers = 0;                  // shapes that move on their own
  bool crossing = false;           // movers slide across other shapes
  double mover_speed_px_s = 60;    // typical speed of a mover at speed 1
  // The sensor.
  double contrast_threshold = 0.2; // log-intensity step per event
  double threshold_sigma = 0.03;   // pixel-to-pixel threshold mismatch (std dev)
  TimeUs refractory_us = 100;
  double jitter_us = 20.0;         // timestamp jitter (std dev)
  double noise_hz = 0.2;           // background activity per pixel
  int hot_pixels = 0;              // pixels that fire on their own ...
  double hot_pixel_hz = 200;       // ... this often
};

// Parses "still", "translation", "rotation", "zoom", "6dof" or "shake"; returns false for
// anything else.
bool parse_motion(const std::string& name, Motion& out);
const char* motion_name(Motion m);

struct TruthSample {
  TimeUs t;
  int object;
  double x, y;        // px, sensor coordinates of the pixel centres
  double radius = 0;  // px, radius of a circle around the centre that holds the outline
};

class SceneGenerator {
 public:
  explicit SceneGenerator(const SceneConfig& config);
  ~SceneGenerator();
  SceneGenerator(const SceneGenerator&) = delete;
  SceneGenerator& operator=(const SceneGenerator&) = delete;

  // Appends the next events (labelled) and ground-truth samples, in time order; returns
  // false once the scene is over and everything was returned.
  bool next(std::vector<LabelledEvent>& events, std::vector<TruthSample>& truth);

  SensorSize sensor() const { return {config_.width, config_.height}; }
  int object_count() const;
  std::string object_name(int i) const;
  double progress() const;

 private:
  struct Impl;
  SceneConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace evms::gen
