#include "host/read/labelled_csv.h"

#include <algorithm>
#include <charconv>
#include <string>

namespace evms::read {

LabelledCsvReader::LabelledCsvReader(const std::string& path) : in_(path) {
  // Comment lines may come first: evms writes "# sensor WxH" there.
  std::string_view header;
  bool more = false;
  while ((more = in_.next_line(header)) && header.rfind('#', 0) == 0) {
  }
  if (!more) fail(path, InputPosition::line(in_.line()), "no rows: expected 't_us,x,y,p,label' rows, with or without that header");
  if (is_csv_header(header)) {
    columns_ = csv_columns_of_header(header, path, in_.line());
  } else {
    // Without a header the columns are the event readers' (CsvColumns::headerless), the label
    // required; this first line is then a row.
    columns_ = CsvColumns::headerless();
    ++columns_.count;  // the label that may follow the event's four
    columns_.label_may_follow = false;
    columns_.separator = separator_of_row(header);
    first_row_ = header;
  }
  if (!columns_.has(CsvField::kLabel)) {
    fail(path, InputPosition::line(in_.line()), "bad header: no label column (the columns are " + columns_.joined() + "; the labels are read from a column named label)");
  }
}

bool LabelledCsvReader::next(LabelledEvent& out) {
  std::string held;  // a headerless file's first row, parsed on the first call only
  if (!first_row_.empty()) held.swap(first_row_);
  std::string_view line = held;
  while (line.empty()) {
    if (!in_.next_line(line)) return false;
  }
  const auto refuse = [&](const std::string& what) { fail(in_.path(), InputPosition::line(in_.line()), what); };
  long long t = 0, x = 0, y = 0, p = 0, label = 0;
  const char* at = line.data();
  const char* const end = line.data() + line.size();
  for (int i = 0; i < columns_.count; ++i) {
    const std::string& name = columns_.name[static_cast<size_t>(i)];
    if (i > 0) {
      if (at == end || *at != columns_.separator) refuse("truncated row: expected " + std::to_string(columns_.count) + " fields");
      ++at;
    }
    const CsvField f = columns_.field[static_cast<size_t>(i)];
    if (f == CsvField::kUnread) {
      const std::optional<size_t> field_end = csv_field_end({at, static_cast<size_t>(end - at)}, columns_.separator);
      if (!field_end) refuse("field '" + name + "': " + kCsvQuoteRefused);
      at += *field_end;
      continue;
    }
    if (f == CsvField::kSeconds) {
      const char* field_end = std::find(at, end, columns_.separator);
      const auto us = seconds_to_us({at, static_cast<size_t>(field_end - at)});
      if (!us) refuse("field '" + name + "' is missing or not a decimal number of seconds");
      t = *us;
      at = field_end;
      continue;
    }
    long long& v = f == CsvField::kMicroseconds ? t : f == CsvField::kX ? x : f == CsvField::kY ? y : f == CsvField::kPolarity ? p : label;
    const auto [q, ec] = std::from_chars(at, end, v);
    if (ec != std::errc()) refuse("field '" + name + "' is missing or not an integer (expected " + columns_.joined() + ")");
    at = q;
  }
  if (at != end) refuse("more than " + std::to_string(columns_.count) + " fields");
  if (x < 0 || x > 65535 || y < 0 || y > 65535 || (p != 0 && p != 1)) refuse("value out of range");
  if (label < kLabelLostOnLink || label > INT32_MAX) {
    refuse("label " + std::to_string(label) + " is not a track ID, -1 (noise) or -2 (lost on the board's link)");
  }
  out.event = {t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint8_t>(p)};
  out.label = static_cast<std::int32_t>(label);
  return true;
}

}  // namespace evms::read
