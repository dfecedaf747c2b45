// Text for a Markdown table cell: a '|' in it would end the cell, so it is escaped. The tables
// written from one description (docs/parameters.md by `evms params --markdown`, docs/registers.md
// by host/tools/rtl_gen) put free text such as "|ON - OFF|" in cells.
#pragma once

#include <string>
#include <string_view>

namespace evms {

inline std::string markdown_cell(std::string_view text) {
  std::string cell;
  for (const char c : text) {
    if (c == '|') cell += '\\';
    cell += c;
  }
  return cell;
}

}  // namespace evms
