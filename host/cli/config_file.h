// The --config file: a YAML map of method parameters (name: value) and a preset, read in one
// place so that the command line and the fuzz target (tests/fuzz/fuzz_config.cpp) take the same
// path through it.
#pragma once

#include <string>

#include "types/params.h"

namespace evms::cli {

// The preset and settings of a --config YAML file; throws read::InputError naming the file and
// line of what is wrong, and nothing else.
Method method_from_config(const std::string& path);
// A --config file with every parameter at its default, each under a comment saying what it is.
std::string config_yaml();

}  // namespace evms::cli
