#include "host/cli/config_file.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "host/read/input_error.h"

namespace evms::cli {

Method method_from_config(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw read::InputError(path + ": cannot open the configuration file");
  } catch (const YAML::Exception& e) {
    read::fail(path, read::InputPosition::line(static_cast<std::uint64_t>(e.mark.line + 1)), "bad YAML: " + e.msg);
  }
  Method method;
  if (!root || root.IsNull()) return method;
  if (!root.IsMap()) read::fail(path, {}, "expected a map of parameter: value");
  for (const auto& entry : root) {
    const auto line = read::InputPosition::line(static_cast<std::uint64_t>(entry.first.Mark().line + 1));
    // A key may be any node in YAML ("? [a, b]"); a parameter's name is a plain word.
    if (!entry.first.IsScalar()) read::fail(path, line, "expected a parameter name before ':', found a list or map");
    const std::string key = entry.first.Scalar();
    if (!entry.second.IsScalar()) read::fail(path, line, key + ": expected a single value");
    const std::string value = entry.second.Scalar();
    if (key == "preset") {
      const auto names = preset_names();
      if (std::find(names.begin(), names.end(), value) == names.end()) read::fail(path, line, "unknown preset '" + read::printable(value) + "'");
      method.preset = value;
      continue;
    }
    const auto table = param_table();
    const auto info = std::find_if(table.begin(), table.end(), [&](const ParamInfo& i) { return key == i.name; });
    if (info == table.end()) read::fail(path, line, "unknown parameter '" + read::printable(key) + "' (evms params lists them)");
    Params scratch;
    if (std::string error = set_param(scratch, *info, value); !error.empty()) read::fail(path, line, error);
    method.settings.emplace_back(info->name, value);
  }
  return method;
}

std::string config_yaml() {
  const Params defaults;
  std::string s = "# evms method parameters: evms run --config FILE. Each line is a parameter at its default;\n"
                  "# the command line wins over this file. From evms params --config.\n"
                  "preset: evms\n";
  for (const ParamInfo& info : param_table()) {
    s += std::string("# ") + info.help + (*info.unit ? std::string(" [") + info.unit + "]" : "") + "\n";
    s += std::string(info.name) + ": " + param_text(defaults, info) + "\n";
  }
  return s;
}

}  // namespace evms::cli
