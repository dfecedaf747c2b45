#include "host/read/csv_columns.h"

#include <cctype>
#include <charconv>
#include <string>
#include <utility>

#include "host/read/input_error.h"

namespace evms::read {
namespace {

constexpr std::pair<std::string_view, CsvField> kColumnNames[] = {
    {"t_us", CsvField::kMicroseconds},      {"t", CsvField::kMicroseconds},        {"ts", CsvField::kMicroseconds},
    {"timestamp", CsvField::kMicroseconds}, {"timestamp_us", CsvField::kMicroseconds},
    {"time", CsvField::kMicroseconds},      {"time_us", CsvField::kMicroseconds},
    {"t_s", CsvField::kSeconds},            {"time_s", CsvField::kSeconds},         {"timestamp_s", CsvField::kSeconds},
    {"x", CsvField::kX},                    {"y", CsvField::kY},
    {"p", CsvField::kPolarity},             {"pol", CsvField::kPolarity},           {"polarity", CsvField::kPolarity},
    {"label", CsvField::kLabel}};

}  // namespace

std::optional<CsvField> column_named(std::string_view name) {
  std::string lower(name);
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (const auto& [n, f] : kColumnNames) {
    if (n == lower) return f;
  }
  return std::nullopt;
}

CsvColumns CsvColumns::metavision() {
  CsvColumns c;
  c.field = {CsvField::kX, CsvField::kY, CsvField::kPolarity, CsvField::kMicroseconds, CsvField::kLabel};
  c.name = {"x", "y", "p", "t", "label"};
  c.label_may_follow = false;
  return c;
}

std::string CsvColumns::joined() const {
  std::string s;
  for (int i = 0; i < count; ++i) s += (i ? "," : "") + name[static_cast<size_t>(i)];
  return s;
}

std::string CsvColumns::unread() const {
  std::string s;
  for (int i = 0; i < count; ++i) {
    if (field[static_cast<size_t>(i)] == CsvField::kUnread) s += (s.empty() ? "" : ",") + name[static_cast<size_t>(i)];
  }
  return s;
}

std::string CsvColumns::described() const {
  const std::string not_read = unread();
  return joined() + (not_read.empty() ? "" : " (not read: " + not_read + ")");
}

bool CsvColumns::has(CsvField f) const {
  for (int i = 0; i < count; ++i) {
    if (field[static_cast<size_t>(i)] == f) return true;
  }
  return false;
}

bool is_csv_header(std::string_view line) {
  return !line.empty() && (std::isalpha(static_cast<unsigned char>(line[0])) || line[0] == '"' || line[0] == ',');
}

ColumnsByName::ColumnsByName(const std::string& path, InputPosition where, std::string prefix, std::string noun)
    : path_(path), where_(where), prefix_(std::move(prefix)), noun_(std::move(noun)) {
  columns_.count = 0;
  columns_.label_may_follow = false;
}

void ColumnsByName::refuse(const std::string& what) const { fail(path_, where_, prefix_ + what); }

CsvField ColumnsByName::add(std::string_view raw) {
  if (columns_.count == CsvColumns::kMost) refuse("more than " + std::to_string(CsvColumns::kMost) + " " + noun_ + "s");
  const CsvField f = column_named(raw).value_or(CsvField::kUnread);
  const bool time = f == CsvField::kMicroseconds || f == CsvField::kSeconds;
  if (f != CsvField::kUnread && (time ? columns_.has_time() : columns_.has(f))) {
    refuse(noun_ + " '" + std::string(raw) + "' repeats " + (time ? "the time" : "a " + noun_));
  }
  std::string name(raw);
  if (f != CsvField::kUnread) {
    for (char& ch : name) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  columns_.field[static_cast<size_t>(columns_.count)] = f;
  columns_.name[static_cast<size_t>(columns_.count)] = name;
  ++columns_.count;
  return f;
}

CsvColumns ColumnsByName::done() const {
  const auto require = [&](bool there, const char* what) {
    if (!there) {
      refuse(std::string("no ") + what + " " + noun_ + " (the " + noun_ + "s are " + columns_.joined() +
             (columns_.unread().empty() ? "" : "; the names evms reads: " + std::string(kColumnNamesKnown)) + ")");
    }
  };
  require(columns_.has_time(), "time");
  require(columns_.has(CsvField::kX), "x");
  require(columns_.has(CsvField::kY), "y");
  require(columns_.has(CsvField::kPolarity), "polarity");
  return columns_;
}

char separator_of_header(std::string_view line) {
  bool seen[3] = {false, false, false}, quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;  // a name in quotes may hold any of them
    if (!quoted) seen[0] |= c == ',', seen[1] |= c == ';', seen[2] |= c == '\t';
  }
  return seen[0] ? ',' : seen[1] ? ';' : seen[2] ? '\t' : ',';
}

char separator_of_row(std::string_view row) {
  return row.find(',') == std::string_view::npos && row.find(';') != std::string_view::npos ? ';' : ',';
}

std::optional<size_t> csv_field_end(std::string_view row, char separator) {
  const size_t first = row.find_first_not_of(' ');
  if (first == std::string_view::npos || row[first] != '"') {
    const size_t end = row.find(separator);
    return end == std::string_view::npos ? row.size() : end;
  }
  size_t at = first + 1;
  for (;;) {
    const size_t quote = row.find('"', at);
    if (quote == std::string_view::npos) return std::nullopt;
    if (quote + 1 < row.size() && row[quote + 1] == '"') {
      at = quote + 2;  // "" inside the quotes
      continue;
    }
    size_t end = row.find_first_not_of(" \r", quote + 1);
    if (end == std::string_view::npos) return row.size();
    if (row[end] != separator) return std::nullopt;
    return end;
  }
}

std::string_view csv_field_text(std::string_view field) {
  while (!field.empty() && (field.front() == ' ')) field.remove_prefix(1);
  while (!field.empty() && (field.back() == ' ' || field.back() == '\r')) field.remove_suffix(1);
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = field.substr(1, field.size() - 2);
  return field;
}

CsvColumns csv_columns_of_header(std::string_view line, const std::string& path, std::uint64_t line_no) {
  ColumnsByName columns(path, InputPosition::line(line_no), "bad header: ", "column");
  const char separator = separator_of_header(line);
  for (int n = 1, more = 1; more; ++n) {
    const std::optional<size_t> split = csv_field_end(line, separator);
    if (!split) fail(path, InputPosition::line(line_no), "bad header: column " + std::to_string(n) + ": " + kCsvQuoteRefused);
    more = *split < line.size();
    std::string_view raw = csv_field_text(line.substr(0, *split));
    line.remove_prefix(more ? *split + 1 : line.size());
    if (raw.empty()) {
      fail(path, InputPosition::line(line_no),
           "bad header: column " + std::to_string(n) + " has no name (pandas writes its index so; save with index=False)");
    }
    columns.add(raw);
  }
  CsvColumns done = columns.done();
  done.separator = separator;
  return done;
}

std::optional<TimeUs> seconds_to_us(std::string_view f) {
  const size_t dot = f.find('.');
  const std::string_view whole = f.substr(0, dot);
  const std::string_view frac = dot == std::string_view::npos ? std::string_view{} : f.substr(dot + 1);
  const auto digits = [](std::string_view s) { return s.find_first_not_of("0123456789") == std::string_view::npos; };
  if (whole.empty() || !digits(whole) || !digits(frac) || whole.size() > 12) return std::nullopt;
  TimeUs us = 0;
  for (char c : whole) us = us * 10 + (c - '0');
  TimeUs micro = 0;
  for (size_t i = 0; i < 6; ++i) micro = micro * 10 + (i < frac.size() ? frac[i] - '0' : 0);
  if (frac.size() > 6 && frac[6] >= '5') ++micro;  // round half up
  return us * 1000000 + micro;
}

std::optional<SensorSize> sensor_size_of(std::string_view text, char separator) {
  const char* const end = text.data() + text.size();
  int w = 0, h = 0;
  const auto [p, ec] = std::from_chars(text.data(), end, w);
  if (ec != std::errc() || p == end || *p != separator) return std::nullopt;
  const auto [q, ec2] = std::from_chars(p + 1, end, h);
  if (ec2 != std::errc() || q != end || w <= 0 || h <= 0 || w > 65535 || h > 65535) return std::nullopt;
  return SensorSize{w, h};
}

}  // namespace evms::read
