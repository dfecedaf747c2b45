#pragma once

#include <string>

#include "host/gen/scene_generator.h"

namespace evms::gen {
// Reads "gen://SCENE?key=value&..." (see generated_source.cpp); throws read::InputError.
SceneConfig parse_scene_uri(const std::string& uri);
}  // namespace evms::gen
