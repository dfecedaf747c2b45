// The two text formats.
//  - RPG Event Camera Dataset events.txt: "t x y p" per line, t in seconds with up to 9
//    decimals (rounded to the nearest microsecond), p 0 = OFF, 1 = ON. Fields are separated
//    by spaces or tabs. The dataset's DAVIS240C is 240x180, the default size.
//  - CSV "t_us,x,y,p" with an optional fifth column (a label, ignored here), as evms itself
//    writes. A header line names the columns in any order (host/read/csv_columns.h lists the
//    names), as pandas and spreadsheets write them; without one the rows are t_us,x,y,p[,label].
//  - Metavision's CSV (metavision_file_to_csv): a first line "%geometry:W,H", then "x,y,p,t"
//    rows, t in microseconds.
// Blank lines and lines starting with '#' are skipped. p may also be -1 for OFF. A first line
// "# sensor WxH" (evms writes one) or "%geometry:W,H" gives the sensor size; without it the size
// comes from --width/--height, else from a first pass over the rows (the smallest usual sensor
// that holds every event), else (a pipe) the DAVIS240C's 240x180 is assumed; an assumed size is
// said.
#include <sys/stat.h>

#include <algorithm>
#include <charconv>
#include <limits>
#include <optional>
#include <string_view>

#include "host/read/csv_columns.h"
#include "host/read/event_source.h"

namespace evms::read {
namespace {

constexpr SensorSize kDavis240{240, 180};

class TextSource final : public FileEventSource {
 public:
  TextSource(ByteReader in, const SourceOptions& o, bool csv) : TextSource(std::move(in), o, csv, false) {
    const std::optional<SensorSize> sensor = sensor_;
    if (!sensor && (o.width <= 0 || o.height <= 0)) {
      if (const std::optional<SensorSize> extent = extent_of_rows(in_.path(), o, csv)) {
        set_sensor(std::nullopt, *extent, kSensorAssumedFromExtent);
        return;
      }
    }
    set_sensor(sensor, kDavis240, "assumed: the file does not say (DAVIS240C); pass --width and --height");
  }

 protected:
  bool decode_more() override {
    std::string_view line;
    for (int n = 0; n < 4096; ++n) {
      if (!in_.next_line(line)) return false;
      parse(line);
    }
    return true;
  }

 private:
  // Reads what comes before the rows; a source that only scans (`scan_only`) starts no ordering
  // and takes no event, but the extent of the rows' coordinates.
  TextSource(ByteReader in, const SourceOptions& o, bool csv, bool scan_only)
      : FileEventSource(std::move(in), csv ? "CSV" : "RPG events.txt", o), csv_(csv), scan_only_(scan_only) {
    if (in_.peek(kUtf8ByteOrderMark.size()) == kUtf8ByteOrderMark) in_.skip(kUtf8ByteOrderMark.size());
    sensor_ = sensor_comment();
    if (csv_ && !sensor_) sensor_ = metavision_geometry();
    if (csv_) {
      header_ahead();
      describe_columns();
    }
  }

  // A first pass over a regular file's rows, up to its end or its first bad row (the second
  // pass reports that row after the events before it): the smallest usual sensor that holds
  // every coordinate, or nothing for a pipe or a coordinate beyond any sensor (the second
  // pass then names the event outside the 240x180 it assumes).
  static std::optional<SensorSize> extent_of_rows(const std::string& path, const SourceOptions& o, bool csv) {
    struct stat st {};
    if (stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
    TextSource scan(ByteReader(path), o, csv, true);
    std::string_view line;
    try {
      while (scan.in_.next_line(line)) scan.parse(line);
    } catch (const InputError&) {
    }
    if (scan.extent_beyond_sensors_) return std::nullopt;
    return smallest_usual_sensor_holding(scan.extent_width_, scan.extent_height_);
  }

  // Every parsed row ends here.
  void take(TimeUs t, long x, long y, bool on) {
    records_ = true;
    if (!scan_only_) {
      emit(t, x, y, on, InputPosition::line(in_.line()));
      return;
    }
    if (x < 0 || y < 0) return;  // the second pass names it
    if (x >= kMaxSensorSide || y >= kMaxSensorSide) extent_beyond_sensors_ = true;
    extent_width_ = std::max(extent_width_, x + 1);
    extent_height_ = std::max(extent_height_, y + 1);
  }

  // "# sensor WxH" on the first line.
  std::optional<SensorSize> sensor_comment() {
    const std::string_view tag = "# sensor ";
    if (in_.peek(tag.size()) != tag) return std::nullopt;
    std::string_view head = in_.peek(64);
    head = head.substr(tag.size(), head.find('\n') == std::string_view::npos ? std::string_view::npos : head.find('\n') - tag.size());
    if (!head.empty() && head.back() == '\r') head.remove_suffix(1);
    if (const auto size = sensor_size_of(head, 'x')) return size;
    fail(in_.path(), InputPosition::line(1), "bad sensor comment: expected '# sensor WxH'");
  }

  // Metavision's "%geometry:W,H" on the first line; its rows are then x,y,p,t.
  std::optional<SensorSize> metavision_geometry() {
    std::string_view line;
    const std::string_view tag = "%geometry:";
    if (in_.peek(tag.size()) != tag || !in_.next_line(line)) return std::nullopt;
    const auto size = sensor_size_of(line.substr(tag.size()), ',');
    if (!size) bad("bad header: expected '%geometry:W,H'");
    metavision_ = true;
    columns_ = CsvColumns::metavision();
    return size;
  }

  // Reads the header line, if there is one, before any row, so that the format names the
  // columns; parse() then passes over it.
  void header_ahead() {
    const std::string_view ahead = in_.peek(1 << 16);
    size_t at = 0;
    std::uint64_t line_no = in_.line();
    while (at < ahead.size()) {
      const size_t nl = ahead.find('\n', at);
      if (nl == std::string_view::npos) return;  // a longer stretch of comments: parse() reads the header
      std::string_view line = ahead.substr(at, nl - at);
      ++line_no;
      at = nl + 1;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      const size_t first = line.find_first_not_of(" \t");
      if (first == std::string_view::npos || line[first] == '#') continue;
      if (is_csv_header(line.substr(first))) {
        read_header(line.substr(first), line_no);
      } else {
        columns_.separator = separator_of_row(line);
      }
      return;
    }
  }

  void read_header(std::string_view line, std::uint64_t line_no) {
    columns_ = csv_columns_of_header(line, in_.path(), line_no);
    describe_columns();
    header_read_ = true;
  }

  // Whenever the columns are known: the format names them, and the one-pass reader knows
  // whether it can take the rows (it reads integers only).
  void describe_columns() {
    info_.format = "CSV " + columns_.described() + (metavision_ ? " (Metavision)" : "");
    has_seconds_ = columns_.has(CsvField::kSeconds);
  }

  [[noreturn]] void bad(const std::string& what) const {
    fail(in_.path(), InputPosition::line(in_.line()), what);
  }

  // Splits off the next field; separators are the CSV's (',' unless its header used ';' or a
  // tab), blanks otherwise.
  std::string_view field(std::string_view& rest, const char* name, bool may_be_empty = false) const {
    if (!csv_) {
      size_t b = rest.find_first_not_of(" \t");
      rest = b == std::string_view::npos ? std::string_view{} : rest.substr(b);
    }
    size_t end = std::string_view::npos;
    if (csv_) {
      const std::optional<size_t> csv_end = csv_field_end(rest, columns_.separator);
      if (!csv_end) bad(std::string("field '") + name + "': " + kCsvQuoteRefused);
      if (*csv_end < rest.size()) end = *csv_end;
    } else {
      end = rest.find_first_of(" \t");
    }
    std::string_view f = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
    if (csv_) f = csv_field_text(f);
    if (f.empty() && !may_be_empty) bad(std::string("missing field '") + name + "' (truncated record)");
    return f;
  }

  long integer(std::string_view f, const char* name) const {
    long v = 0;
    auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec == std::errc::result_out_of_range) {
      bad(std::string("field '") + name + "' = '" + std::string(f) + "' is out of range (at most " + std::to_string(std::numeric_limits<long>::max()) + ")");
    }
    if (ec != std::errc() || ptr != f.data() + f.size()) {
      bad(std::string("field '") + name + "' = '" + std::string(f) + "' is not an integer");
    }
    return v;
  }

  // Seconds with a decimal fraction, exactly to the microsecond (no binary floating point).
  TimeUs seconds(std::string_view f) const {
    if (const auto us = seconds_to_us(f)) return *us;
    bad("timestamp '" + std::string(f) + "' is not a non-negative decimal number of seconds");
  }

  // An RPG time: seconds. A whole number of a million or more seconds (11.6 days) in a file
  // whose times have had no decimal point is a count of microseconds, which read as seconds
  // would spread the events over weeks: refused, saying how to give microseconds.
  TimeUs rpg_seconds(std::string_view f) {
    const TimeUs t = seconds(f);
    if (f.find('.') != std::string_view::npos) {
      decimal_seen_ = true;
    } else if (!decimal_seen_ && t >= kWholeSecondsRefused * 1000000) {
      bad("timestamp '" + std::string(f) + "' has no decimal point and would be " + std::to_string(t / 86400000000) +
          " days as seconds, the RPG format's unit; for microseconds write a CSV whose header names the column t_us");
    }
    return t;
  }
  static constexpr TimeUs kWholeSecondsRefused = 1000000;

  // The usual line, read in one pass: "t x y p" (t seconds with a fraction) or "t_us,x,y,p[,label]"
  // with digits only and no blanks inside a CSV row. Anything else (a comment, a header, a
  // negative coordinate, extra blanks, a bad field) is left to parse(), which reads it or names
  // what is wrong; what this accepts, parse() would read to the same event.
  bool parse_usual(std::string_view line) {
    const char* p = line.data();
    const char* const end = p + line.size();
    const auto digit = [&](const char* q) { return q < end && static_cast<unsigned>(*q - '0') < 10; };
    const auto blanks = [&] {
      const char* start = p;
      while (p < end && (*p == ' ' || *p == '\t')) ++p;
      return p > start;
    };
    const auto number = [&](long& v, int most) {
      if (!digit(p)) return false;
      v = 0;
      for (int n = 0; digit(p); ++p, ++n) {
        if (n == most) return false;
        v = v * 10 + (*p - '0');
      }
      return true;
    };
    TimeUs t = 0;
    long x = 0, y = 0, pol = 0;
    if (csv_) {
      if (has_seconds_) return false;
      long label = 0;
      for (int i = 0; i < columns_.count; ++i) {
        if (i > 0 && (p == end || *p++ != columns_.separator)) return false;
        const CsvField f = columns_.field[static_cast<size_t>(i)];
        if (f == CsvField::kUnread) {
          if (p < end && *p == '"') return false;  // parse() reads quotes
          while (p < end && *p != columns_.separator) ++p;
          continue;
        }
        if (f == CsvField::kLabel && p < end && *p == '-') ++p;
        long& v = f == CsvField::kMicroseconds ? t : f == CsvField::kX ? x : f == CsvField::kY ? y : f == CsvField::kPolarity ? pol : label;
        if (!number(v, f == CsvField::kMicroseconds ? 18 : f == CsvField::kPolarity ? 1 : 9)) return false;
      }
      if (columns_.label_may_follow && p < end && *p == columns_.separator) {
        ++p;
        if (p < end && *p == '-') ++p;
        if (!number(label, 9)) return false;
      }
      if (p != end) return false;
    } else {
      blanks();
      long whole = 0;
      if (!number(whole, 12)) return false;
      TimeUs micro = 0;
      if (p < end && *p == '.') {
        decimal_seen_ = true;
        ++p;
        int n = 0;
        for (; digit(p); ++p, ++n) {
          if (n < 6) micro = micro * 10 + (*p - '0');
          else if (n == 6 && *p >= '5') ++micro;  // round half up on the seventh digit
        }
        for (; n < 6; ++n) micro *= 10;
      }
      t = whole * 1000000 + micro;
      if (!decimal_seen_ && whole >= kWholeSecondsRefused) return false;  // parse() refuses it
      if (!blanks() || !number(x, 9) || !blanks() || !number(y, 9) || !blanks() || !number(pol, 1)) return false;
      blanks();
      if (p != end) return false;
    }
    if (pol > 1) return false;
    take(t, x, y, pol == 1);
    return true;
  }

  void parse(std::string_view line) {
    if (parse_usual(line)) return;
    size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') return;
    if (csv_ && !records_ && !header_ && is_csv_header(line.substr(first))) {
      if (!header_read_) read_header(line.substr(first), in_.line());
      header_ = true;
      return;
    }
    if (!csv_ && !records_ && names_columns(line.substr(first))) {
      bad("'" + printable(line.substr(first, 40)) + "' is not a row of time (s), x, y and polarity; a header naming the columns " +
          "is read in a CSV file, whose columns are separated by commas, semicolons or tabs");
    }
    std::string_view rest = line.substr(first);
    TimeUs t = 0;
    long x = 0, y = 0, p = 0;
    if (csv_) {
      for (int i = 0; i < columns_.count; ++i) {
        const char* name = columns_.name[static_cast<size_t>(i)].c_str();
        const CsvField holds = columns_.field[static_cast<size_t>(i)];
        // A last column not read may be empty, with or without its comma.
        if (holds == CsvField::kUnread && rest.empty() && i + 1 == columns_.count) break;
        const std::string_view f = field(rest, name, holds == CsvField::kUnread);
        switch (holds) {
          case CsvField::kMicroseconds:
            if (f.find('.') != std::string_view::npos) {
              bad(std::string("field '") + name + "' = '" + std::string(f) +
                  "' is not an integer number of microseconds (a column named t_s holds seconds)");
            }
            t = integer(f, name);
            break;
          case CsvField::kSeconds: t = seconds(f); break;
          case CsvField::kX: x = integer(f, name); break;
          case CsvField::kY: y = integer(f, name); break;
          case CsvField::kPolarity: p = polarity(f, name); break;
          case CsvField::kLabel: integer(f, name); break;
          case CsvField::kUnread: break;
        }
      }
      if (columns_.label_may_follow && !rest.empty()) integer(field(rest, "label"), "label");
      if (!rest.empty()) bad("more than " + std::to_string(columns_.count + (columns_.label_may_follow ? 1 : 0)) + " fields");
    } else {
      t = rpg_seconds(field(rest, "t"));
      x = integer(field(rest, "x"), "x");
      y = integer(field(rest, "y"), "y");
      p = polarity(field(rest, "p"), "p");
      size_t more = rest.find_first_not_of(" \t");
      if (more != std::string_view::npos) bad("more than 4 fields");
    }
    take(t, x, y, p == 1);
  }

  // Every word of the line, between blanks, is a column's name ("t x y p"): a header.
  static bool names_columns(std::string_view line) {
    bool named = false;
    for (size_t at = line.find_first_not_of(" \t"); at != std::string_view::npos; at = line.find_first_not_of(" \t", at)) {
      const size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
      if (!column_named(line.substr(at, end - at))) return false;
      named = true;
      at = end;
    }
    return named;
  }

  long polarity(std::string_view f, const char* name) const {
    const long p = integer(f, name);
    if (p == 0 || p == 1 || p == -1) return p;
    std::string hint;
    if (csv_ && !header_ && columns_.field[0] == CsvField::kMicroseconds) {
      hint = "; rows of x,y,p,t, as Metavision's tools write them, need the header line 'x,y,p,t'";
    }
    bad("polarity " + std::to_string(p) + " is not 0, 1 or -1" + hint);
  }

  bool csv_;
  bool scan_only_;
  std::optional<SensorSize> sensor_;  // from the file's first line
  long extent_width_ = 1, extent_height_ = 1;  // one past the largest x and y a scan met
  bool extent_beyond_sensors_ = false;
  bool decimal_seen_ = false;  // an RPG time with a decimal point was read
  bool records_ = false;  // a record was read (a header may only come before)
  bool header_ = false;   // the header was passed (a second one is a bad record)
  bool header_read_ = false;  // the header's columns were read (ahead of the rows, or when met)
  bool metavision_ = false;   // a "%geometry:W,H" line came first
  CsvColumns columns_;
  bool has_seconds_ = false;  // a time column in seconds (columns_.has(CsvField::kSeconds))
};

}  // namespace

std::unique_ptr<EventSource> open_rpg_text(ByteReader in, const SourceOptions& o) {
  return std::make_unique<TextSource>(std::move(in), o, false);
}

std::unique_ptr<EventSource> open_csv(ByteReader in, const SourceOptions& o) {
  return std::make_unique<TextSource>(std::move(in), o, true);
}

}  // namespace evms::read
