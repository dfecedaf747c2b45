// The columns of an event CSV: which field of a row holds the time, x, y, the polarity and a
// label. A header line names them in any order, as pandas, spreadsheets and other tools write
// them; the event reader (formats/text_formats.cpp) and the scoring reader (labelled_csv.h)
// take the same names.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "types/event.h"
#include "host/read/input_error.h"

namespace evms::read {

// What a column holds: times are integer microseconds unless the column says seconds. A column
// of a name evms does not know is not read (kUnread), and said so.
enum class CsvField : std::uint8_t { kMicroseconds, kSeconds, kX, kY, kPolarity, kLabel, kUnread };

struct CsvColumns {
  static constexpr int kMost = 16;
  std::array<CsvField, kMost> field{CsvField::kMicroseconds, CsvField::kX, CsvField::kY, CsvField::kPolarity,
                                    CsvField::kLabel};
  std::array<std::string, kMost> name{"t_us", "x", "y", "p", "label"};  // as messages name them
  int count = 4;                 // fields in a row
  bool label_may_follow = true;  // a fifth field, a label, may follow (no header said otherwise)
  char separator = ',';          // between fields: ',' unless the header used ';' or a tab

  // Rows without a header: t_us,x,y,p with an optional label.
  static CsvColumns headerless() { return {}; }
  // Metavision's rows (metavision_file_to_csv): x,y,p,t.
  static CsvColumns metavision();

  std::string joined() const;
  // The names of the columns not read, comma-joined; empty when every column is read.
  std::string unread() const;
  // For the format line: the columns, and those not read.
  std::string described() const;
  bool has(CsvField f) const;
  bool has_time() const { return has(CsvField::kMicroseconds) || has(CsvField::kSeconds); }
};

// What a column of this name holds, case aside; nothing for a name evms does not know. NumPy
// files' field names (formats/npy.cpp) go by the same names.
std::optional<CsvField> column_named(std::string_view name);
// The names column_named() knows, for messages.
inline constexpr const char* kColumnNamesKnown =
    "t_us, t, ts, timestamp or time in microseconds, or t_s in seconds; x; y; p, pol or polarity; and optionally label";

// Builds the columns from their names, one at a time: a CSV header's columns or a NumPy
// array's fields (`noun` says which in messages). A name evms does not know is a column not
// read; a repeated name, more than kMost columns, and at the end a missing time, x, y or
// polarity fail with `path` at `where`, after `prefix`.
class ColumnsByName {
 public:
  ColumnsByName(const std::string& path, InputPosition where, std::string prefix, std::string noun);
  CsvField add(std::string_view name);
  CsvColumns done() const;

 private:
  [[noreturn]] void refuse(const std::string& what) const;

  CsvColumns columns_;
  std::string path_;
  InputPosition where_;
  std::string prefix_, noun_;
};

// A line of names, not numbers: it starts with a letter, a quote, or a column without a name.
bool is_csv_header(std::string_view line);

// The separator a header line uses: ',' when it holds one, else ';' (spreadsheets where the
// comma is the decimal mark) or a tab (tab-separated values), else ','.
char separator_of_header(std::string_view line);

// The separator of a row without a header: ';' when it holds one and no comma (a spreadsheet
// whose decimal mark is the comma), else ','.
char separator_of_row(std::string_view row);

// Where the CSV field at the start of `row` ends: the index of the separator after it, or
// row.size(). A field that opens with a double quote (blanks before it aside) runs to its
// closing quote, separators inside it included, and "" inside it is a quote (RFC 4180). Nothing
// when that quote does not close in the row, or text other than blanks follows it.
std::optional<size_t> csv_field_end(std::string_view row, char separator);
inline constexpr const char* kCsvQuoteRefused = "a quoted field does not close before the end of the row, or has more than blanks after its closing quote";

// A field without the blanks around it and the quotes that enclose it.
std::string_view csv_field_text(std::string_view field);

// The columns a header line names (case and quotes aside), split at its separator
// (separator_of_header); t, x, y and p must each be there once, and other names are columns not
// read. Anything else fails with the file and line.
CsvColumns csv_columns_of_header(std::string_view line, const std::string& path, std::uint64_t line_no);

// Seconds with a decimal fraction of up to 9 digits, rounded half up to the microsecond without
// binary floating point; nothing when `f` is not such a number.
std::optional<TimeUs> seconds_to_us(std::string_view f);

// "WxH" or "W,H" (by `separator`), each side 1..65535, and nothing more.
std::optional<SensorSize> sensor_size_of(std::string_view text, char separator);

}  // namespace evms::read
