// The scene family: randomized labelled scenes on which the method's choices are made and
// checked. A member is a scene type and a seed; the seed draws everything else:
//
//   sensor        128x128, 240x180, 346x260 or 640x480
//   shapes        1-12 of any kind (the nine poster shapes, thin bars, concave L, cross, ring,
//                 chevron), 5 to 60 px across at 240x180 (scaled with the sensor), a quarter
//                 of them only slightly darker than the poster
//   speed         0.25x to 4x
//   sensor noise  0.05 to 2 Hz a pixel, 0-4 hot pixels, threshold mismatch 0.02-0.06,
//                 refractory period 50 us to 1 ms
//
// and the type sets the motion:
//   still         the camera stands; 1-4 shapes move on their own
//   translation, rotation, zoom, 6dof, shake
//                 the camera moves over still shapes
//   crossing      the camera drifts slowly; 2-4 shapes slide across others (occlusions)
//
// Seeds split the family: the tuning split (seeds 1-999) is where choices are made, the
// validation split (seeds 1000 and up) where they are checked. Neither sees the other.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "host/gen/scene_generator.h"

namespace evms::gen {

std::span<const char* const> family_types();
bool is_family_type(const std::string& type);

enum class Split { kTuning, kValidation };
inline constexpr std::uint64_t kValidationSeedBase = 1000;
inline Split split_of(std::uint64_t seed) { return seed >= kValidationSeedBase ? Split::kValidation : Split::kTuning; }
// The n-th seed (0-based) of a split.
inline std::uint64_t split_seed(Split s, int n) { return (s == Split::kValidation ? kValidationSeedBase : 1) + static_cast<std::uint64_t>(n); }

// What a member may have pinned instead of drawn from the seed: the sensor (object sizes and
// speeds scale with it), the number of shapes and the background activity. 0 (-1 for the
// noise) leaves the draw; every other draw stays that of the seed.
struct FamilyPins {
  int width = 0, height = 0;
  int objects = 0;
  double noise_hz = -1;
};

// The member (type, seed) of the family; throws std::invalid_argument for an unknown type.
SceneConfig family_scene(const std::string& type, std::uint64_t seed, const FamilyPins& pins = {});

// The paper's scenes: the shapes poster at 240x180 seen by a translating, rotating or 6-DoF
// camera (the Event Camera Dataset's shapes_translation, shapes_rotation, shapes_6dof).
SceneConfig paper_scene(Motion motion, std::uint64_t seed, double duration_s, double speed = 1.0);

// One line that says what a member holds ("crossing 346x260, 7 shapes (2 moving), speed 1.3x,
// noise 0.4 Hz, 1 hot pixel").
std::string describe(const SceneConfig& c);

}  // namespace evms::gen
