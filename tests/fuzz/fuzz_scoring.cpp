// libFuzzer target for the files `evms metrics` scores: the input, behind the header each file
// starts with, goes into a memory file read to the end as the labelled events
// (host/read/labelled_csv.h) and as a tracks.csv (host/read/tracks_csv.h); and alone, as labelled
// events whose header, if any, is the input's own. A reader may reject
// any input, with read::InputError only: any other exception, a crash, a sanitizer report, a hang
// (-timeout) or an allocation over -rss_limit_mb is a bug.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>

#include "host/read/input_error.h"
#include "host/read/labelled_csv.h"
#include "host/read/tracks_csv.h"

namespace {

// The path of a memory file holding `head` and then the input.
std::string memory_file(const std::string& head, const std::uint8_t* data, size_t size) {
  static const int fd = memfd_create("evms-fuzz", 0);
  if (fd < 0 || ftruncate(fd, 0) != 0) std::abort();
  if (pwrite(fd, head.data(), head.size(), 0) != static_cast<ssize_t>(head.size())) std::abort();
  if (size > 0 && pwrite(fd, data, size, static_cast<off_t>(head.size())) != static_cast<ssize_t>(size)) std::abort();
  return "/proc/self/fd/" + std::to_string(fd);
}

// Reads a labelled-event file to its end.
void read_labels(const std::string& path) {
  try {
    evms::read::LabelledCsvReader labels(path);
    evms::LabelledEvent e;
    while (labels.next(e)) {
    }
  } catch (const evms::read::InputError&) {
    // Rejected with the project's own error: what bad input must get.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  read_labels(memory_file("# sensor 240x180\nt_us,x,y,p,label\n", data, size));
  read_labels(memory_file("", data, size));
  try {
    (void)evms::read::read_tracks_csv(memory_file("t_us,track_id,state,x,y,vx,vy,events\n", data, size));
  } catch (const evms::read::InputError&) {
  }
  return 0;
}
