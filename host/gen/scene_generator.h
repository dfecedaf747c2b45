// A labelled-scene generator in the spirit of the Event Camera Dataset's shapes sequences:
// a poster of flat shapes of different contrasts seen by a moving event camera.
//
// Scene: nine shapes (circle, ellipse, triangle, square, rectangle, pentagon, hexagon, star,
// diamond) on a white poster larger than the field of view, two of which slide across the
// poster in front of others (occlusions). The camera translates, rotates, or does a 6-DoF-like
// mix of both with zoom; shapes leave and re-enter the field of view. --speed scales the
// motion's time, as the paper's speed factors did; sensor properties stay in real time.
//
// Sensor: each pixel compares its log intensity with the level of its last event and fires
// one event per contrast threshold crossed, at the linearly interpolated crossing time. The
// ON and OFF thresholds of every pixel are drawn once (mismatch); a pixel cannot fire again
// within the refractory period; timestamps get Gaussian jitter; background activity fires
// random pixels as a Poisson process. Events are emitted in time order.
//
// Labels: an event is labelled with the topmost shape covering its pixel (or the shape that
// just left it); noise events are labelled -1. Ground truth gives each object's geometric
// centre every millisecond while its whole outline is inside the sensor.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "golden/event.h"
#include "host/gen/random.h"

namespace evms::gen {

enum class Motion { kTranslation, kRotation, kSixDof };

struct SceneConfig {
  Motion motion = Motion::kRotation;
  double speed = 1.0;              // time scale of the motion
  std::uint64_t seed = 1;
  double duration_s = 5.0;
  int width = 240, height = 180;   // DAVIS240C
  double contrast_threshold = 0.2; // log-intensity step per event
  double threshold_sigma = 0.03;   // pixel-to-pixel threshold mismatch (std dev)
  TimeUs refractory_us = 100;
  double jitter_us = 20.0;         // timestamp jitter (std dev)
  double noise_hz = 0.2;           // background activity per pixel
};

// Parses "translation", "rotation" or "6dof"; returns false for anything else.
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
