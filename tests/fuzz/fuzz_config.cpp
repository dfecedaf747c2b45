// libFuzzer target for the --config reader (host/cli/config_file.h): the input is the YAML file.
// It may be rejected with read::InputError only; yaml-cpp's own exceptions, a crash, a
// sanitizer report or a hang are bugs.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>

#include "host/cli/config_file.h"
#include "host/read/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  static const int fd = memfd_create("evms-fuzz-config", 0);
  if (fd < 0 || ftruncate(fd, 0) != 0) std::abort();
  if (size > 0 && pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) std::abort();
  try {
    (void)evms::cli::method_from_config("/proc/self/fd/" + std::to_string(fd));
  } catch (const evms::read::InputError&) {
    // Rejected with the project's own error: what a bad file must get.
  }
  return 0;
}
