// A method on the scene family (host/gen/family.h): every member of a split run and scored the
// same way, F and ARI over 10 ms chunks (noise counted as singletons), tracking against the
// true centres, and the cost.
#pragma once

#include <string>
#include <vector>

#include "types/params.h"
#include "host/eval/evaluation.h"
#include "host/eval/identity_metrics.h"
#include "host/gen/family.h"

namespace evms::eval {

struct FamilyScene {
  std::string type;
  std::uint64_t seed = 0;
  Scene scene;
};

// A member: a family type (host/gen/family.h), or "paper-translation", "paper-rotation" or
// "paper-6dof" for the paper's scenes (the shapes poster at 240x180, kPaperSceneSeconds long).
// `pins` apply to the family's types, not to the paper's scenes.
gen::SceneConfig member_scene(const std::string& type, std::uint64_t seed, const gen::FamilyPins& pins = {});
inline constexpr double kPaperSceneSeconds = 1.0;
inline const std::vector<std::string> kPaperSceneTypes = {"paper-translation", "paper-rotation", "paper-6dof"};

// `seeds` members of every type in `types` from one split.
std::vector<FamilyScene> generate_family(gen::Split split, int seeds, const std::vector<std::string>& types, int jobs,
                                         const gen::FamilyPins& pins = {});

// How family scores are taken: 10 ms chunks, as the independent scenes were scored.
inline constexpr Chunking kFamilyChunking{Chunking::Kind::kTime, 10000};

struct SceneResult {
  ClusteringScores scores;
  TrackingReport tracking;
  IdentityScores identity;
  double noise_share = 0;                 // events labelled -1
  std::int64_t events = 0;
  std::int64_t kernel_evaluations = 0;
  double wall_s = 0;
};

struct TypeSummary {
  std::string type;
  int scenes = 0;
  double f = 0, ari = 0;                  // means over the type's scenes
  double worst_f = 0;
};

struct FamilyResult {
  std::vector<SceneResult> scenes;        // in the order of the FamilyScene list
  std::vector<TypeSummary> types;
  double mean_f = 0, mean_ari = 0;        // over every scene, each weighing the same
  double worst_type_f = 0;                // the lowest of the types' means
  ErrorStats tracking;                    // pooled over every scene: Kalman estimate against the true centre
  ErrorStats tracking_to_events;          // ... against the centre of the object's labelled events (the paper's)
  ErrorStats events_centre;               // pooled: the labelled events' centre against the true centre (TrackingReport::all_events_centre)
  ErrorStats velocity;                    // pooled: the Kalman velocity against the true centre's, px/s
  ClearMot mot;                           // CLEAR MOT, summed and pooled over every scene
  double idf1 = 0;                        // mean over scenes
  double id_switches_per_object = 0;      // over every scene
  double kernel_evaluations_per_event = 0;
  double events_per_s = 0;                // the backend's throughput, events held in memory
};

FamilyResult evaluate_family(const std::vector<FamilyScene>& family, const Method& method, const std::string& backend,
                             int jobs);

// The same members under several methods at once (one pass of the thread pool).
std::vector<FamilyResult> evaluate_family(const std::vector<FamilyScene>& family, const std::vector<Method>& methods,
                                          const std::string& backend, int jobs);

}  // namespace evms::eval
