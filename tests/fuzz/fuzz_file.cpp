// libFuzzer target for the file readers: the input, behind the magic bytes of the format this
// target is built for (EVMS_FUZZ_FORMAT names it, so that the fuzzer explores that decoder and
// not the detection), goes into a memory file that evms reads to the end as `evms run` would.
// A reader may reject any input, with read::InputError only: any other exception, a crash, a
// sanitizer report, a hang (-timeout) or an allocation over -rss_limit_mb is a bug.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "host/read/event_source.h"
#include "host/read/input_error.h"

namespace {

constexpr std::string_view kFormat = EVMS_FUZZ_FORMAT;

// The bytes every file of the format starts with.
std::string prefix() {
  using namespace std::string_view_literals;
  if (kFormat == "aedat2") return "#!AER-DAT2.0\r\n";
  if (kFormat == "aedat3") return "#!AER-DAT3.1\r\n#Format: RAW\r\n#Source 1: DAVIS240C\r\n#!END-HEADER\r\n";
  if (kFormat == "aedat4") return "#!AER-DAT4.0\r\n";
  if (kFormat == "evt2") return "% evt 2.0\n% geometry 346x260\n% end\n";
  if (kFormat == "evt21") return "% evt 2.1\n% geometry 346x260\n% end\n";
  if (kFormat == "evt3") return "% evt 3.0\n% geometry 346x260\n% end\n";
  if (kFormat == "dat") return "% Data file containing Event2D events.\n% Version 2\n";
  if (kFormat == "csv") return "";  // a CSV's header is its own (host/read/csv_columns.h): the fuzzer writes it
  if (kFormat == "text") return "# sensor 346x260\n";
  if (kFormat == "ros2") return std::string("SQLite format 3\0"sv);
  if (kFormat == "ros1") return "#ROSBAG V2.0\n";
  if (kFormat == "mcap") return "\x89MCAP0\r\n";
  if (kFormat == "npy") return std::string("\x93NUMPY\x01\x00"sv);
  std::abort();
}

int memory_file() {
  static const int fd = memfd_create("evms-fuzz", 0);
  return fd;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  static const std::string head = prefix();
  const int fd = memory_file();
  if (fd < 0 || ftruncate(fd, 0) != 0) std::abort();
  if (pwrite(fd, head.data(), head.size(), 0) != static_cast<ssize_t>(head.size())) std::abort();
  if (size > 0 && pwrite(fd, data, size, static_cast<off_t>(head.size())) != static_cast<ssize_t>(size)) std::abort();
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  try {
    evms::read::SourceOptions options;
    options.width = 346, options.height = 260;  // for the formats whose files do not say
    auto source = evms::read::open_source(path, options);
    std::vector<evms::Event> batch(4096);
    while (source->read(batch) > 0) {
    }
    (void)source->skipped();
  } catch (const evms::read::InputError&) {
    // Rejected with the project's own error: what bad input must get.
  }
  return 0;
}
