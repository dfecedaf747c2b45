// Reader of labelled-event CSV files (`t_us,x,y,p,label`), as `evms run` and `evms gen`
// write them, for scoring: a header names the columns, in any order (csv_columns.h), and
// must have a label; without one the rows are `t_us,x,y,p,label`. Comment lines before the
// header or the first row (evms writes "# sensor WxH" there) are skipped. Bad rows stop with
// the file and line.
#pragma once

#include <string>

#include "types/event.h"
#include "host/read/byte_reader.h"
#include "host/read/csv_columns.h"

namespace evms::read {

class LabelledCsvReader {
 public:
  explicit LabelledCsvReader(const std::string& path);
  // The next row; false at the end of the file.
  bool next(LabelledEvent& out);
  std::uint64_t line() const { return in_.line(); }
  const std::string& path() const { return in_.path(); }

 private:
  ByteReader in_;
  CsvColumns columns_;
  std::string first_row_;  // a headerless file's first row, read while looking for a header
};

}  // namespace evms::read
