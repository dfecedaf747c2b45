// Running a backend over events held in memory and collecting everything it outputs, for
// evaluation, sweeps and tests.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "types/output.h"
#include "host/backend/backend.h"
#include "host/gen/scene_generator.h"

namespace evms::eval {

// A generated scene, whole: events with their true labels and the objects' true centres.
struct Scene {
  gen::SceneConfig config;
  SensorSize sensor;
  std::vector<Event> events;
  std::vector<std::int32_t> truth;          // object index, or -1 for noise
  std::vector<gen::TruthSample> centres;    // every ms, per object wholly in view
  std::vector<std::string> object_names;
};

Scene generate_scene(const gen::SceneConfig& config);

struct RunResult {
  std::vector<std::int32_t> labels;         // one per input event
  std::vector<TrackUpdate> tracks;
  std::vector<PacketSummary> packets;
  backend::BackendStats stats;
  double wall_s = 0;
};

RunResult run_backend(const std::string& backend, const Params& params, SensorSize sensor,
                      std::span<const Event> events);
// The same, on a backend already made (one the registry does not list, say).
RunResult run_backend(backend::Backend& backend, std::span<const Event> events);

}  // namespace evms::eval
