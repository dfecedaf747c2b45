// Reader of labelled-event CSV files (`t_us,x,y,p,label`), as `evms run` and `evms gen`
// write them, for scoring. Comment lines before the header (evms writes "# sensor WxH" there)
// are skipped. Bad rows stop with the file and line.
#pragma once

#include <string>

#include "types/event.h"
#include "host/read/byte_reader.h"

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
};

}  // namespace evms::read
