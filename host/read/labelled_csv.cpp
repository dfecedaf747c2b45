#include "host/read/labelled_csv.h"

#include <charconv>
#include <string>

namespace evms::read {

LabelledCsvReader::LabelledCsvReader(const std::string& path) : in_(path) {
  // Comment lines may come first: evms writes "# sensor WxH" there.
  std::string_view header;
  bool more = false;
  while ((more = in_.next_line(header)) && header.rfind('#', 0) == 0) {
  }
  if (!more || header.rfind("t_us,x,y,p,label", 0) != 0) {
    fail(path, InputPosition::line(in_.line()), "bad header: expected 't_us,x,y,p,label'");
  }
}

bool LabelledCsvReader::next(LabelledEvent& out) {
  std::string_view line;
  do {
    if (!in_.next_line(line)) return false;
  } while (line.empty());
  long long v[5];
  const char* p = line.data();
  const char* end = line.data() + line.size();
  static const char* kNames[5] = {"t_us", "x", "y", "p", "label"};
  for (int i = 0; i < 5; ++i) {
    auto [q, ec] = std::from_chars(p, end, v[i]);
    if (ec != std::errc()) {
      fail(in_.path(), InputPosition::line(in_.line()),
           std::string("field '") + kNames[i] + "' is missing or not an integer (expected t_us,x,y,p,label)");
    }
    p = q;
    if (i < 4) {
      if (p == end || *p != ',') fail(in_.path(), InputPosition::line(in_.line()), "truncated row: expected 5 fields");
      ++p;
    }
  }
  if (p != end) fail(in_.path(), InputPosition::line(in_.line()), "more than 5 fields");
  if (v[1] < 0 || v[1] > 65535 || v[2] < 0 || v[2] > 65535 || (v[3] != 0 && v[3] != 1)) {
    fail(in_.path(), InputPosition::line(in_.line()), "value out of range");
  }
  if (v[4] < kLabelLostOnLink || v[4] > INT32_MAX) {
    fail(in_.path(), InputPosition::line(in_.line()),
         "label " + std::to_string(v[4]) + " is not a track ID, -1 (noise) or -2 (lost on the board's link)");
  }
  out.event = {v[0], static_cast<std::uint16_t>(v[1]), static_cast<std::uint16_t>(v[2]), static_cast<std::uint8_t>(v[3])};
  out.label = static_cast<std::int32_t>(v[4]);
  return true;
}

}  // namespace evms::read
