// rtl/generated/ and docs/registers.md are what the generator writes today from hls/core/:
// re-run it and compare every file.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/command.h"
#include "tests/support/encoders.h"

namespace evms::test {
namespace {

TEST(RtlGenerated, FilesAreCurrent) {
  TempDir rtl, docs;
  const auto r = run_command(std::string(EVMS_RTL_GEN) + " " + rtl.path("") + " " + docs.path(""));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::filesystem::path source(EVMS_SOURCE_DIR);
  int files = 0;
  auto compare = [&](const TempDir& written, const std::filesystem::path& committed, const std::string& folder) {
    for (const auto& e : std::filesystem::directory_iterator(written.path(""))) {
      ++files;
      const auto name = e.path().filename();
      ASSERT_TRUE(std::filesystem::exists(committed / name)) << folder << name.string() << " is not committed";
      EXPECT_TRUE(same_text(read_file(e.path().string()), read_file((committed / name).string())))
          << folder << name.string() << " is stale: run 'cmake --build build --target rtl-generated'";
    }
  };
  compare(rtl, source / "rtl" / "generated", "rtl/generated/");
  compare(docs, source / "docs", "docs/");
  // Per build: .svh and .cmake; shared: 21 interface files, 4 tables, registers.md.
  EXPECT_GE(files, 3 * 2 + 21 + 4 + 1);
}

}  // namespace
}  // namespace evms::test
