// gen://SCENE?key=value&... : a generated labelled scene (host/gen/) as an event source, so that
// every subcommand can run without a file (generated_source.cpp says which keys).
#pragma once

#include <string>

#include "host/gen/scene_generator.h"

namespace evms::read {
// The scene a gen:// URI names; throws InputError naming what is wrong with it.
gen::SceneConfig parse_scene_uri(const std::string& uri);
}  // namespace evms::read
