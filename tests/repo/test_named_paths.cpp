// Every path into the project that a source file, script or document names exists: a comment
// that points a reader at a file points at one. A path is a word that starts with one of the
// project's folders (golden/, hls/, rtl/, ...) and ends in a file extension; it is looked up from
// the project's root and from the naming file's own folder (a document's relative link, a
// CMakeLists.txt's own sources).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kFolders[] = {"golden/", "hls/", "rtl/", "sim/", "host/", "tests/", "constraints/", "docs/", "types/", ".ci/"};
// Files the check reads, and which a path may name; and files a path may name only.
constexpr std::string_view kSourceExtensions[] = {".h", ".cpp", ".sv", ".svh", ".vlt", ".md", ".py", ".sh", ".tcl", ".pcf", ".xdc", ".f", ".cmake"};
constexpr std::string_view kDataExtensions[] = {".json", ".mem", ".txt", ".yml", ".yaml", ".hex"};

bool is_path_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '/' || c == '-'; }

template <std::size_t N>
bool has_extension_in(const fs::path& file, const std::string_view (&extensions)[N]) {
  const std::string ext = file.extension().string();
  return std::find(std::begin(extensions), std::end(extensions), ext) != std::end(extensions);
}

bool scanned(const fs::path& file) {
  return file.filename() == "CMakeLists.txt" || has_extension_in(file, kSourceExtensions) ||
         file.parent_path().filename() == ".ci";  // its scripts have no extension
}

// A folder of the tree that is not the project's source: git's, a build's, or a fetched one.
bool skipped_folder(const fs::path& dir) {
  const std::string name = dir.filename().string();
  return name == ".git" || name.rfind("build", 0) == 0 || fs::exists(dir / "CMakeCache.txt");
}

// "FILE:LINE names PATH, which does not exist" for every such path under root.
std::vector<std::string> missing_named_paths(const fs::path& root) {
  std::vector<std::string> missing;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_directory()) {
      if (skipped_folder(it->path())) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || !scanned(it->path())) continue;
    std::ifstream in(it->path());
    std::string line;
    for (int line_no = 1; std::getline(in, line); ++line_no) {
      for (const std::string_view folder : kFolders) {
        for (std::size_t at = line.find(folder); at != std::string::npos; at = line.find(folder, at + 1)) {
          if (at > 0 && is_path_char(line[at - 1])) continue;  // inside a longer path or word
          std::size_t end = at;
          while (end < line.size() && is_path_char(line[end])) ++end;
          std::string path = line.substr(at, end - at);
          while (!path.empty() && (path.back() == '.' || path.back() == '/')) path.pop_back();
          if (!has_extension_in(path, kSourceExtensions) && !has_extension_in(path, kDataExtensions)) continue;
          if (fs::exists(root / path) || fs::exists(it->path().parent_path() / path)) continue;
          std::ostringstream os;
          os << fs::relative(it->path(), root).string() << ":" << line_no << " names " << path << ", which does not exist";
          missing.push_back(os.str());
        }
      }
    }
  }
  return missing;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

}  // namespace

TEST(NamedPaths, EveryPathTheProjectNamesExists) {
  const auto missing = missing_named_paths(EVMS_SOURCE_DIR);
  EXPECT_TRUE(missing.empty()) << joined(missing);
}

TEST(NamedPaths, TheCheckNamesAStalePathAndPassesLiveAndRelativeOnes) {
  const fs::path root = fs::temp_directory_path() / ("evms_named_paths_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(root);
  fs::create_directories(root / "hls" / "core");
  fs::create_directories(root / "tests" / "hls");
  fs::create_directories(root / "build" / "hls");
  // The names are put together here, so that this file does not name them itself.
  const std::string gone = std::string("hls") + "/core/gone.h", old = std::string("tests") + "/hls/old.cpp";
  const std::string relative = std::string("hls") + "/test_core.cpp";  // from tests/CMakeLists.txt
  std::ofstream(root / "hls" / "core" / "core.h") << "// see hls/core/core.h and " << gone << ".\n";
  std::ofstream(root / "tests" / "CMakeLists.txt") << "add(" << relative << ")\n# " << old << "\n";
  std::ofstream(root / "tests" / "hls" / "test_core.cpp") << "// a/hls/not_ours.h, docs/ and rtl/core are not files\n";
  std::ofstream(root / "build" / "hls" / "x.cpp") << "// " << gone << " in a build folder\n";
  const auto missing = missing_named_paths(root);
  fs::remove_all(root);
  ASSERT_EQ(missing.size(), 2u) << joined(missing);
  const std::string all = joined(missing);
  EXPECT_NE(all.find("hls/core/core.h:1 names " + gone + ", which does not exist"), std::string::npos) << all;
  EXPECT_NE(all.find("tests/CMakeLists.txt:2 names " + old + ", which does not exist"), std::string::npos) << all;
}
