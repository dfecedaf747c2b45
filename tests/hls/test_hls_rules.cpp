// hls/ stays within what a C++ synthesis tool accepts: it compiles with -fno-exceptions
// -fno-rtti -Werror (loop labels and HLS pragmas are for the synthesis tool, so those two
// warnings are off), includes no container, string, stream or allocation header, calls no
// function recursively, and names no heap or exception construct.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <functional>
#include <regex>
#include <set>
#include <sstream>

#include "tests/support/command.h"
#include "tests/support/encoders.h"

namespace evms::test {
namespace {

namespace fs = std::filesystem;

struct Compiled {
  CommandResult result;
  std::string callgraph;
};

Compiled compile_top(const TempDir& dir) {
  const std::string out = dir.path("top.o");
  const std::string cmd = std::string(EVMS_HLS_RULES_CXX) + " -std=c++17 -O1 -fno-exceptions -fno-rtti -Werror -Wall -Wextra" +
                          " -Wno-unknown-pragmas -Wno-unused-label -H -fcallgraph-info -I" + EVMS_SOURCE_DIR + " -c " + EVMS_SOURCE_DIR +
                          "/hls/top.cpp -o " + out;
  Compiled c{run_command("cd " + dir.path("") + " && " + cmd), ""};
  for (const auto& e : fs::directory_iterator(dir.path(""))) {
    if (e.path().extension() == ".ci") {
      std::stringstream ss;
      ss << std::ifstream(e.path()).rdbuf();
      c.callgraph += ss.str();
    }
  }
  return c;
}

TEST(HlsRules, CompilesWithoutExceptionsOrRtti) {
  TempDir dir;
  const Compiled c = compile_top(dir);
  EXPECT_EQ(c.result.exit_code, 0) << c.result.err;
}

TEST(HlsRules, IncludesNoContainersStreamsOrAllocation) {
  TempDir dir;
  const Compiled c = compile_top(dir);
  ASSERT_EQ(c.result.exit_code, 0) << c.result.err;
  const std::regex forbidden(R"(/(vector|string|map|unordered_map|set|unordered_set|list|deque|memory|iostream|ostream|istream|sstream|fstream|functional|new|stdexcept|exception)$)");
  std::istringstream lines(c.result.err);
  int headers = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] != '.') continue;
    ++headers;
    const std::string path = line.substr(line.find(' ') + 1);
    EXPECT_FALSE(std::regex_search(path, forbidden)) << "hls/ pulls in " << path;
  }
  EXPECT_GT(headers, 5) << "the include trace (-H) was not captured";
}

// -fcallgraph-info writes each function as a node and each call as an edge; a cycle among
// hls's own functions is recursion.
TEST(HlsRules, NoRecursion) {
  TempDir dir;
  const Compiled c = compile_top(dir);
  ASSERT_EQ(c.result.exit_code, 0) << c.result.err;
  ASSERT_FALSE(c.callgraph.empty()) << "no call graph written";
  std::map<std::string, std::set<std::string>> calls;
  const std::regex edge(R"re(edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)")re");
  for (std::sregex_iterator it(c.callgraph.begin(), c.callgraph.end(), edge), end; it != end; ++it) calls[(*it)[1]].insert((*it)[2]);
  ASSERT_FALSE(calls.empty());
  std::map<std::string, int> state;  // 1 = on the stack, 2 = done
  std::string cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& f) {
    if (state[f] == 1) return cycle = f, true;
    if (state[f] == 2) return false;
    state[f] = 1;
    for (const auto& g : calls[f]) {
      if (visit(g)) return true;
    }
    state[f] = 2;
    return false;
  };
  for (const auto& [f, targets] : calls) EXPECT_FALSE(visit(f)) << "recursion through " << cycle;
}

TEST(HlsRules, SourcesNameNoHeapOrExceptionConstructs) {
  const std::regex forbidden(R"(\bnew\b|\bdelete\b|\bmalloc\b|\bfree\s*\(|\bthrow\b|\btry\b|\bcatch\b|dynamic_cast|typeid|std::(vector|string|map|list|deque|function|unique_ptr|shared_ptr)\b)");
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(std::string(EVMS_SOURCE_DIR) + "/hls")) {
    if (e.path().extension() != ".h" && e.path().extension() != ".cpp") continue;
    ++files;
    std::ifstream in(e.path());
    int n = 0;
    for (std::string line; std::getline(in, line);) {
      ++n;
      const auto comment = line.find("//");
      const std::string code = line.substr(0, comment);
      EXPECT_FALSE(std::regex_search(code, forbidden)) << e.path().string() << ":" << n << ": " << line;
    }
  }
  EXPECT_GT(files, 10);
}

}  // namespace
}  // namespace evms::test
