#include <filesystem>

#include "tests/support/read_all.h"

namespace evms::test {

std::string shared_data_dir() {
  const std::filesystem::path dir = std::filesystem::path(EVMS_SOURCE_DIR) / ".." / "shared" / "data" / "real";
  return std::filesystem::exists(dir / "README.md") ? dir.lexically_normal().string() : "";
}

}  // namespace evms::test
