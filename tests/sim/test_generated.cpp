// rtl/generated/ is what the generator writes today: re-run it and compare every file.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/command.h"
#include "tests/support/encoders.h"

namespace evms::test {
namespace {

TEST(RtlGenerated, FilesAreCurrent) {
  TempDir dir;
  const auto r = run_command(std::string(EVMS_RTL_GEN) + " " + dir.path(""));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::filesystem::path committed = std::filesystem::path(EVMS_SOURCE_DIR) / "rtl" / "generated";
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path(""))) {
    ++files;
    const auto name = e.path().filename();
    ASSERT_TRUE(std::filesystem::exists(committed / name)) << name << " is not committed";
    EXPECT_EQ(read_file(e.path().string()), read_file((committed / name).string())) << "rtl/generated/" << name.string()
                                                      << " is stale: run 'cmake --build build --target rtl-generated'";
  }
  EXPECT_GE(files, 12);
}

}  // namespace
}  // namespace evms::test
