#include "host/read/tracks_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "host/read/byte_reader.h"
#include "host/read/input_error.h"

namespace evms::read {
namespace {

constexpr std::string_view kLayout = "t_us,track_id,state,x,y,vx,vy";  // the columns read; more may follow

// The comma-separated fields of one line.
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  for (size_t start = 0;;) {
    const size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

template <typename T>
bool parse_whole(std::string_view field, T& value) {
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  return ec == std::errc() && end == field.data() + field.size();
}

}  // namespace

std::vector<TrackUpdate> read_tracks_csv(const std::string& path) {
  ByteReader in(path);
  std::string_view line;
  bool more = false;
  while ((more = in.next_line(line)) && line.rfind('#', 0) == 0) {
  }
  const std::string layout(kLayout);
  if (!more) fail(path, InputPosition::line(in.line()), "empty: expected a header '" + layout + ",...'");
  const std::vector<std::string_view> header = split(line), columns = split(kLayout);
  if (header.size() < columns.size() || !std::equal(columns.begin(), columns.end(), header.begin())) {
    fail(path, InputPosition::line(in.line()), "bad header: expected '" + layout + "' first (evms run's tracks.csv)");
  }
  std::vector<TrackUpdate> updates;
  while (in.next_line(line)) {
    if (line.empty()) continue;
    const auto where = InputPosition::line(in.line());
    const std::vector<std::string_view> f = split(line);
    if (f.size() != header.size()) {
      fail(path, where, std::to_string(f.size()) + " fields where the header has " + std::to_string(header.size()));
    }
    TrackUpdate u;
    long long t = 0, id = 0;
    if (!parse_whole(f[0], t) || t < 0) fail(path, where, "t_us '" + printable(f[0]) + "' is not a non-negative integer");
    if (!parse_whole(f[1], id) || id < 0 || id > std::numeric_limits<std::int32_t>::max()) {
      fail(path, where, "track_id '" + printable(f[1]) + "' is not a track ID (a non-negative 32-bit integer)");
    }
    if (f[2] == "confirmed") {
      u.state = TrackState::kConfirmed;
    } else if (f[2] == "tentative") {
      u.state = TrackState::kTentative;
    } else {
      fail(path, where, "state '" + printable(f[2]) + "' is neither tentative nor confirmed");
    }
    double* const value[] = {&u.x, &u.y, &u.vx, &u.vy};
    for (size_t i = 0; i < 4; ++i) {
      if (!parse_whole(f[3 + i], *value[i]) || !std::isfinite(*value[i])) {
        fail(path, where, std::string(columns[3 + i]) + " '" + printable(f[3 + i]) + "' is not a finite number");
      }
    }
    u.t = t, u.id = static_cast<std::int32_t>(id);
    u.zx = u.x, u.zy = u.y;  // the file holds the estimate only
    updates.push_back(u);
  }
  return updates;
}

}  // namespace evms::read
