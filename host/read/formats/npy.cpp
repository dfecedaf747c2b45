// NumPy .npy files, format versions 1.0, 2.0 and 3.0: the magic "\x93NUMPY", two version
// bytes, the header's length (2 bytes little-endian in 1.0, 4 after), the header (a Python dict
// literal with the keys 'descr', 'fortran_order' and 'shape'), then the array's bytes.
// Two layouts hold events:
//  - a structured array of N records whose fields go by the names of CSV columns
//    (csv_columns.h), in any order and of any integer type, bool for the polarity and float
//    for a time in seconds (`t_s`), and fields of other names not read: evms's own events.npy,
//    and the arrays tonic and others save;
//  - an integer array of shape (N, 4) or (N, 5) in C order, its columns t_us, x, y, p and a
//    label, as a CSV without a header.
// The file does not say the sensor size: it comes from --width/--height, else it is the
// smallest usual sensor that holds every event (a first pass over the records), and said so.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "host/read/csv_columns.h"
#include "host/read/event_source.h"

namespace evms::read {
namespace {

// A field's scalar type, from a NumPy type string such as "<i8", "|u1" or "|b1".
struct NpyScalar {
  char kind = 0;    // 'b' bool, 'i' signed, 'u' unsigned, 'f' float
  int bytes = 0;
  bool big_endian = false;
};

struct NpyField {
  CsvField holds;
  NpyScalar type;
  size_t offset = 0;
  std::string name;
};

struct NpyLayout {
  std::vector<NpyField> fields;
  size_t record_bytes = 0;
  std::uint64_t records = 0;
  std::uint64_t data_offset = 0;
  std::string describe;  // for the format line: "NPY t,x,y,p,label" or "NPY (N, 4) <i8"
  bool plain = false;    // a plain array, its columns t_us,x,y,p[,label]
};

// The header's dict, read by a cursor over its text; every error names the byte it stopped at.
class NpyHeaderParser {
 public:
  NpyHeaderParser(std::string_view text, std::uint64_t at, const std::string& path) : text_(text), at_(at), path_(path) {}

  NpyLayout parse() {
    NpyLayout layout;
    std::vector<std::pair<std::string, std::string>> structured;  // (name, type string)
    std::string plain;                                            // the type of a plain array
    std::vector<std::uint64_t> shape;
    bool have_descr = false, have_order = false, have_shape = false, fortran = false;
    expect('{');
    while (!take('}')) {
      const std::string key = string();
      expect(':');
      if (key == "descr") {
        have_descr = true;
        if (next_is('[')) {
          structured = fields();
        } else {
          plain = string();
        }
      } else if (key == "fortran_order") {
        have_order = true;
        fortran = boolean();
      } else if (key == "shape") {
        have_shape = true;
        shape = tuple_of_integers();
      } else {
        refuse("a key '" + key + "' that NumPy headers do not have");
      }
      if (!take(',')) {
        expect('}');
        break;
      }
    }
    if (!have_descr || !have_order || !have_shape) refuse("the header lacks 'descr', 'fortran_order' or 'shape'");
    std::uint64_t n = 1;
    for (std::uint64_t d : shape) {
      if (d != 0 && n > std::numeric_limits<std::uint64_t>::max() / d) refuse("a shape of more elements than 2^64");
      n *= d;
    }
    if (!structured.empty()) {
      if (shape.size() != 1) refuse("a structured array of events has one dimension, not " + std::to_string(shape.size()));
      layout.records = n;
      ColumnsByName columns(path_, InputPosition::byte(at_ + pos_), "bad NPY header: ", "field");
      for (const auto& [name, type] : structured) {
        const NpyScalar scalar = scalar_of(type);
        const CsvField holds = columns.add(name);
        check_type(name, holds, scalar);
        layout.fields.push_back({holds, scalar, layout.record_bytes, name});
        layout.record_bytes += static_cast<size_t>(scalar.bytes);
      }
      layout.describe = "NPY " + columns.done().described();
      return layout;
    }
    // A plain array: the columns of a CSV without a header.
    const NpyScalar scalar = scalar_of(plain);
    if (shape.size() != 2 || (shape[1] != 4 && shape[1] != 5)) {
      refuse("a plain array of events has shape (N, 4) or (N, 5), columns t_us,x,y,p[,label]; save a structured array "
             "with named fields for any other layout");
    }
    if (scalar.kind != 'i' && scalar.kind != 'u') refuse("a plain array's columns t_us,x,y,p are integers, not '" + plain + "'");
    if (fortran) refuse("a plain array in Fortran order (save it in C order)");
    layout.records = shape[0];
    layout.plain = true;
    const CsvField columns[] = {CsvField::kMicroseconds, CsvField::kX, CsvField::kY, CsvField::kPolarity, CsvField::kLabel};
    const char* names[] = {"t_us", "x", "y", "p", "label"};
    for (size_t i = 0; i < shape[1]; ++i) {
      layout.fields.push_back({columns[i], scalar, layout.record_bytes, names[i]});
      layout.record_bytes += static_cast<size_t>(scalar.bytes);
    }
    layout.describe = "NPY (N, " + std::to_string(shape[1]) + ") " + plain + " as t_us,x,y,p" + (shape[1] == 5 ? ",label" : "");
    return layout;
  }

 private:
  [[noreturn]] void refuse(const std::string& what) const {
    fail(path_, InputPosition::byte(at_ + pos_), "bad NPY header: " + what);
  }

  void blanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n')) ++pos_;
  }
  bool next_is(char c) {
    blanks();
    return pos_ < text_.size() && text_[pos_] == c;
  }
  bool take(char c) {
    if (!next_is(c)) return false;
    ++pos_;
    return true;
  }
  void expect(char c) {
    if (!take(c)) refuse(std::string("expected '") + c + "'");
  }
  std::string string() {
    blanks();
    if (pos_ >= text_.size() || (text_[pos_] != '\'' && text_[pos_] != '"')) refuse("expected a quoted string");
    const char quote = text_[pos_++];
    const size_t end = text_.find(quote, pos_);
    if (end == std::string_view::npos) refuse("a string without its closing quote");
    std::string s(text_.substr(pos_, end - pos_));
    pos_ = end + 1;
    return s;
  }
  bool boolean() {
    blanks();
    for (const auto& [word, value] : {std::pair{"True", true}, std::pair{"False", false}}) {
      if (text_.substr(pos_, std::strlen(word)) == word) {
        pos_ += std::strlen(word);
        return value;
      }
    }
    refuse("expected True or False");
  }
  std::vector<std::uint64_t> tuple_of_integers() {
    std::vector<std::uint64_t> v;
    expect('(');
    while (!take(')')) {
      blanks();
      std::uint64_t d = 0;
      const auto [p, ec] = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), d);
      if (ec != std::errc()) refuse("expected a dimension");
      pos_ = static_cast<size_t>(p - text_.data());
      v.push_back(d);
      if (!take(',')) {
        expect(')');
        break;
      }
    }
    return v;
  }
  // [('name', 'type'), ...]
  std::vector<std::pair<std::string, std::string>> fields() {
    std::vector<std::pair<std::string, std::string>> v;
    expect('[');
    while (!take(']')) {
      expect('(');
      if (next_is('(')) refuse("a field with a title (save the array without titles)");
      std::string name = string();
      expect(',');
      if (next_is('[') || next_is('(')) refuse("field '" + name + "' is itself structured");
      std::string type = string();
      if (take(',')) refuse("field '" + name + "' is an array in each record");
      expect(')');
      v.emplace_back(std::move(name), std::move(type));
      if (!take(',')) {
        expect(']');
        break;
      }
    }
    if (v.empty()) refuse("a structured array without fields");
    return v;
  }
  NpyScalar scalar_of(const std::string& type) const {
    NpyScalar s;
    // The byte order may be left out ("u1", as NumPy itself accepts).
    const size_t kind_at = !type.empty() && std::strchr("<>|=", type[0]) ? 1 : 0;
    if (type.size() >= kind_at + 2 && std::strchr("biuf", type[kind_at])) {
      s.big_endian = type[0] == '>';
      s.kind = type[kind_at];
      const auto [p, ec] = std::from_chars(type.data() + kind_at + 1, type.data() + type.size(), s.bytes);
      const bool sized = s.kind == 'f' ? (s.bytes == 4 || s.bytes == 8) : (s.bytes == 1 || s.bytes == 2 || s.bytes == 4 || s.bytes == 8);
      if (ec == std::errc() && p == type.data() + type.size() && sized) return s;
    }
    refuse("type '" + type + "' is not a bool, an integer of 1, 2, 4 or 8 bytes, or a float of 4 or 8");
  }
  void check_type(const std::string& name, CsvField holds, const NpyScalar& s) const {
    const bool integer = s.kind == 'i' || s.kind == 'u';
    if (holds == CsvField::kSeconds && s.kind != 'f') refuse("field '" + name + "' holds seconds: a float, not '" + std::string(1, s.kind) + "'");
    if (holds == CsvField::kPolarity && !integer && s.kind != 'b') refuse("field '" + name + "' is a polarity: a bool or an integer");
    if (holds != CsvField::kSeconds && holds != CsvField::kPolarity && holds != CsvField::kUnread && !integer) {
      refuse("field '" + name + "' is an integer" + (holds == CsvField::kMicroseconds ? " number of microseconds (a float field named t_s holds seconds)" : ""));
    }
  }

  std::string_view text_;
  std::uint64_t at_;
  const std::string& path_;
  size_t pos_ = 0;
};

NpyLayout read_npy_header(ByteReader& in) {
  unsigned char lead[12];
  const size_t got = in.read(lead, 10);
  if (got < 10 || std::memcmp(lead, "\x93NUMPY", 6) != 0) fail(in.path(), InputPosition::byte(0), "bad NPY header: truncated");
  const int major = lead[6];
  if (major < 1 || major > 3) fail(in.path(), InputPosition::byte(6), "bad NPY header: version " + std::to_string(major) + " (1, 2 and 3 are known)");
  std::uint64_t length = lead[8] | (lead[9] << 8);
  std::uint64_t at = 10;
  if (major > 1) {
    if (in.read(lead + 10, 2) < 2) fail(in.path(), InputPosition::byte(10), "bad NPY header: truncated");
    length |= (std::uint64_t{lead[10]} << 16) | (std::uint64_t{lead[11]} << 24);
    at = 12;
  }
  if (length > (1u << 20)) fail(in.path(), InputPosition::byte(8), "bad NPY header: a header of " + std::to_string(length) + " bytes");
  std::string text(length, '\0');
  if (in.read(text.data(), length) < length) fail(in.path(), InputPosition::byte(at), "bad NPY header: truncated");
  NpyLayout layout = NpyHeaderParser(text, at, in.path()).parse();
  layout.data_offset = at + length;
  return layout;
}

// One field of a record, as a signed integer (bools and integers) or a double (floats).
std::int64_t integer_of(const unsigned char* b, const NpyScalar& s, bool& out_of_range) {
  std::uint64_t u = 0;
  for (int i = 0; i < s.bytes; ++i) u |= std::uint64_t{b[s.big_endian ? s.bytes - 1 - i : i]} << (8 * i);
  if (s.kind == 'i' && s.bytes < 8 && (u >> (8 * s.bytes - 1)) & 1) u |= ~std::uint64_t{0} << (8 * s.bytes);
  if (s.kind == 'u' && s.bytes == 8 && u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) out_of_range = true;
  return static_cast<std::int64_t>(u);
}
double float_of(const unsigned char* b, const NpyScalar& s) {
  std::uint64_t u = 0;
  for (int i = 0; i < s.bytes; ++i) u |= std::uint64_t{b[s.big_endian ? s.bytes - 1 - i : i]} << (8 * i);
  if (s.bytes == 4) {
    float f;
    const auto w = static_cast<std::uint32_t>(u);
    std::memcpy(&f, &w, 4);
    return f;
  }
  double d;
  std::memcpy(&d, &u, 8);
  return d;
}

class NpySource final : public FileEventSource {
 public:
  NpySource(ByteReader in, const SourceOptions& o) : FileEventSource(std::move(in), "NPY", o), layout_(read_npy_header(in_)) {
    info_.format = layout_.describe;
    // A pipe has no size to check against, nor a second pass: its sensor size must be given.
    const bool regular = in_.size() >= layout_.data_offset;
    if (regular) {
      const std::uint64_t have = in_.size() - layout_.data_offset, held = have / layout_.record_bytes;
      if (held < layout_.records) {
        fail(in_.path(), InputPosition::byte(layout_.data_offset + held * layout_.record_bytes),
             "truncated: the header says " + std::to_string(layout_.records) + " records, the file holds " + std::to_string(held));
      }
      const std::uint64_t want = layout_.records * layout_.record_bytes;  // no more than `have`: no overflow
      if (have > want) {
        fail(in_.path(), InputPosition::byte(layout_.data_offset + want),
             std::to_string(have - want) + (have - want == 1 ? " byte" : " bytes") + " after the header's " +
                 std::to_string(layout_.records) + " records");
      }
    }
    std::optional<SensorSize> extent;
    if (regular && (o.width <= 0 || o.height <= 0)) extent = sensor_holding_every_event();
    set_sensor(std::nullopt, extent, kSensorAssumedFromExtent);
  }

 protected:
  bool decode_more() override {
    std::vector<unsigned char>& r = record_;
    r.resize(layout_.record_bytes);
    for (int n = 0; n < 8192; ++n) {
      if (next_ == layout_.records) return false;
      const std::uint64_t at = in_.offset();
      if (in_.read(r.data(), r.size()) < r.size()) fail(in_.path(), InputPosition::byte(at), "truncated record");
      ++next_;
      const Decoded d = decode(r.data(), at);
      emit(d.t, d.x, d.y, d.p, InputPosition::byte(at));
    }
    return true;
  }

 private:
  struct Decoded {
    TimeUs t = 0;
    long x = 0, y = 0;
    int p = 0;
  };

  Decoded decode(const unsigned char* r, std::uint64_t at) const {
    Decoded d;
    for (const NpyField& f : layout_.fields) {
      const unsigned char* b = r + f.offset;
      if (f.holds == CsvField::kUnread) continue;
      if (f.holds == CsvField::kSeconds) {
        const double s = float_of(b, f.type);
        if (!(s >= 0 && s < 9.2e12)) fail(in_.path(), InputPosition::byte(at + f.offset), "field '" + f.name + "' = " + std::to_string(s) + " s is not a time");
        d.t = std::llround(s * 1e6);
        continue;
      }
      bool out_of_range = false;
      const std::int64_t v = integer_of(b, f.type, out_of_range);
      if (out_of_range) fail(in_.path(), InputPosition::byte(at + f.offset), "field '" + f.name + "' is beyond 2^63");
      switch (f.holds) {
        case CsvField::kMicroseconds: d.t = v; break;
        case CsvField::kX: d.x = static_cast<long>(v); break;
        case CsvField::kY: d.y = static_cast<long>(v); break;
        case CsvField::kPolarity:
          if (v != 0 && v != 1 && v != -1) {
            fail(in_.path(), InputPosition::byte(at + f.offset),
                 "polarity " + std::to_string(v) + " is not 0, 1 or -1" +
                     (layout_.plain ? "; a plain array's columns are t_us,x,y,p: save a structured array with named fields for another order" : ""));
          }
          d.p = v == 1;
          break;
        case CsvField::kLabel:
        case CsvField::kSeconds:
        case CsvField::kUnread: break;
      }
    }
    return d;
  }

  // A first pass over every record's x and y, through a reader of its own.
  std::optional<SensorSize> sensor_holding_every_event() {
    ByteReader scan(in_.path());
    scan.skip(layout_.data_offset);
    std::vector<unsigned char> r(layout_.record_bytes);
    long width = 1, height = 1;
    for (std::uint64_t i = 0; i < layout_.records; ++i) {
      const std::uint64_t at = scan.offset();
      if (scan.read(r.data(), r.size()) < r.size()) break;
      const Decoded d = decode(r.data(), at);
      // Beyond any sensor: nothing is assumed, and the size must be given.
      if (d.x < 0 || d.y < 0 || d.x >= kMaxSensorSide || d.y >= kMaxSensorSide) return std::nullopt;
      width = std::max(width, d.x + 1), height = std::max(height, d.y + 1);
    }
    return smallest_usual_sensor_holding(width, height);
  }

  NpyLayout layout_;
  std::vector<unsigned char> record_;
  std::uint64_t next_ = 0;
};

}  // namespace

std::unique_ptr<EventSource> open_npy(ByteReader in, const SourceOptions& o) {
  return std::make_unique<NpySource>(std::move(in), o);
}

}  // namespace evms::read
