// The two text formats.
//  - RPG Event Camera Dataset events.txt: "t x y p" per line, t in seconds with up to 9
//    decimals (rounded to the nearest microsecond), p 0 = OFF, 1 = ON. Fields are separated
//    by spaces or tabs. The dataset's DAVIS240C is 240x180, the default size.
//  - CSV "t_us,x,y,p" with an optional header line and an optional fifth column (a label,
//    ignored here), as evms itself writes.
// Blank lines and lines starting with '#' are skipped. p may also be -1 for OFF. A first line
// "# sensor WxH" (evms writes one) gives the sensor size; without it the size comes from
// --width/--height, else the DAVIS240C's 240x180 is assumed, and said.
#include <charconv>
#include <optional>
#include <string_view>

#include "host/read/event_source.h"

namespace evms::read {
namespace {

constexpr SensorSize kDavis240{240, 180};

class TextSource final : public FileEventSource {
 public:
  TextSource(ByteReader in, const SourceOptions& o, bool csv)
      : FileEventSource(std::move(in), csv ? "CSV t_us,x,y,p" : "RPG events.txt", o), csv_(csv) {
    if (in_.peek(kUtf8ByteOrderMark.size()) == kUtf8ByteOrderMark) in_.skip(kUtf8ByteOrderMark.size());
    set_sensor(sensor_comment(), kDavis240, "assumed: the file does not say (DAVIS240C); pass --width and --height");
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
  // "# sensor WxH" on the first line.
  std::optional<SensorSize> sensor_comment() {
    const std::string_view head = in_.peek(64);
    const std::string_view tag = "# sensor ";
    if (head.substr(0, tag.size()) != tag) return std::nullopt;
    const std::string_view rest = head.substr(tag.size(), head.find('\n') == std::string_view::npos ? std::string_view::npos : head.find('\n') - tag.size());
    int w = 0, h = 0;
    auto [p, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), w);
    if (ec == std::errc() && p < rest.data() + rest.size() && *p == 'x') {
      auto [q, ec2] = std::from_chars(p + 1, rest.data() + rest.size(), h);
      const bool tail_ok = q == rest.data() + rest.size() || *q == '\r';
      if (ec2 == std::errc() && tail_ok && w > 0 && h > 0 && w <= 65535 && h <= 65535) return SensorSize{w, h};
    }
    fail(in_.path(), InputPosition::line(1), "bad sensor comment: expected '# sensor WxH'");
  }

  [[noreturn]] void bad(const std::string& what) const {
    fail(in_.path(), InputPosition::line(in_.line()), what);
  }

  // Splits off the next field; separators are ',' for CSV, blanks otherwise.
  std::string_view field(std::string_view& rest, const char* name) const {
    if (!csv_) {
      size_t b = rest.find_first_not_of(" \t");
      rest = b == std::string_view::npos ? std::string_view{} : rest.substr(b);
    }
    size_t end = csv_ ? rest.find(',') : rest.find_first_of(" \t");
    std::string_view f = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
    if (csv_) {
      while (!f.empty() && (f.front() == ' ')) f.remove_prefix(1);
      while (!f.empty() && (f.back() == ' ')) f.remove_suffix(1);
    }
    if (f.empty()) bad(std::string("missing field '") + name + "' (truncated record)");
    return f;
  }

  long integer(std::string_view f, const char* name) const {
    long v = 0;
    auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || ptr != f.data() + f.size()) {
      bad(std::string("field '") + name + "' = '" + std::string(f) + "' is not an integer");
    }
    return v;
  }

  // Seconds with a decimal fraction, exactly to the microsecond (no binary floating point).
  TimeUs seconds(std::string_view f) const {
    size_t dot = f.find('.');
    std::string_view whole = f.substr(0, dot);
    std::string_view frac = dot == std::string_view::npos ? std::string_view{} : f.substr(dot + 1);
    auto digits = [](std::string_view s) {
      return s.find_first_not_of("0123456789") == std::string_view::npos;
    };
    if (whole.empty() || !digits(whole) || !digits(frac) || whole.size() > 12) {
      bad("timestamp '" + std::string(f) + "' is not a non-negative decimal number of seconds");
    }
    TimeUs us = 0;
    for (char c : whole) us = us * 10 + (c - '0');
    TimeUs micro = 0;
    for (size_t i = 0; i < 6; ++i) micro = micro * 10 + (i < frac.size() ? frac[i] - '0' : 0);
    if (frac.size() > 6 && frac[6] >= '5') ++micro;  // round half up
    return us * 1000000 + micro;
  }

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
      long us = 0;
      if (!number(us, 18) || p == end || *p++ != ',') return false;
      t = us;
      if (!number(x, 9) || p == end || *p++ != ',' || !number(y, 9) || p == end || *p++ != ',' || !number(pol, 1)) return false;
      if (p < end && *p == ',') {
        ++p;
        if (p < end && *p == '-') ++p;
        long label = 0;
        if (!number(label, 9)) return false;
      }
      if (p != end) return false;
    } else {
      blanks();
      long whole = 0;
      if (!number(whole, 12)) return false;
      TimeUs micro = 0;
      if (p < end && *p == '.') {
        ++p;
        int n = 0;
        for (; digit(p); ++p, ++n) {
          if (n < 6) micro = micro * 10 + (*p - '0');
          else if (n == 6 && *p >= '5') ++micro;  // round half up on the seventh digit
        }
        for (; n < 6; ++n) micro *= 10;
      }
      t = whole * 1000000 + micro;
      if (!blanks() || !number(x, 9) || !blanks() || !number(y, 9) || !blanks() || !number(pol, 1)) return false;
      blanks();
      if (p != end) return false;
    }
    if (pol > 1) return false;
    records_ = true;
    emit(t, x, y, pol == 1, InputPosition::line(in_.line()));
    return true;
  }

  void parse(std::string_view line) {
    if (parse_usual(line)) return;
    size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') return;
    if (csv_ && !records_ && !header_ && std::isalpha(static_cast<unsigned char>(line[first]))) {
      if (line.substr(first).rfind("t_us,x,y,p", 0) != 0) {
        bad("bad header: expected 't_us,x,y,p' (optionally ',label')");
      }
      header_ = true;
      return;
    }
    std::string_view rest = line.substr(first);
    std::string_view ft = field(rest, "t");
    const TimeUs t = csv_ ? integer(ft, "t_us") : seconds(ft);
    const long x = integer(field(rest, "x"), "x");
    const long y = integer(field(rest, "y"), "y");
    const long p = integer(field(rest, "p"), "p");
    if (p != 0 && p != 1 && p != -1) bad("polarity " + std::to_string(p) + " is not 0, 1 or -1");
    if (csv_ && !rest.empty()) integer(field(rest, "label"), "label");
    if (!csv_) {
      size_t more = rest.find_first_not_of(" \t");
      if (more != std::string_view::npos) bad("more than 4 fields");
    } else if (!rest.empty()) {
      bad("more than 5 fields");
    }
    records_ = true;
    emit(t, x, y, p == 1, InputPosition::line(in_.line()));
  }

  bool csv_;
  bool records_ = false;  // a record was read (a header may only come before)
  bool header_ = false;   // the header was read (a second one is a bad record)
};

}  // namespace

std::unique_ptr<EventSource> open_rpg_text(ByteReader in, const SourceOptions& o) {
  return std::make_unique<TextSource>(std::move(in), o, false);
}

std::unique_ptr<EventSource> open_csv(ByteReader in, const SourceOptions& o) {
  return std::make_unique<TextSource>(std::move(in), o, true);
}

}  // namespace evms::read
