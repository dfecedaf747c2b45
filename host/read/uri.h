// "scheme://TARGET?key=value&key=value": the source URIs (gen://, udp://) split into their
// target and settings, in order. A setting without '=' has an empty value.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace evms::read {

struct SourceUri {
  std::string target;                                      // between "://" and '?'
  std::vector<std::pair<std::string, std::string>> query;  // key, value
};

inline SourceUri split_source_uri(const std::string& uri) {
  SourceUri u;
  const size_t start = uri.find("://");
  std::string rest = start == std::string::npos ? uri : uri.substr(start + 3);
  const size_t q = rest.find('?');
  u.target = rest.substr(0, q);
  std::string query = q == std::string::npos ? "" : rest.substr(q + 1);
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string item = query.substr(0, amp);
    query = amp == std::string::npos ? "" : query.substr(amp + 1);
    const size_t eq = item.find('=');
    u.query.emplace_back(item.substr(0, eq), eq == std::string::npos ? "" : item.substr(eq + 1));
  }
  return u;
}

}  // namespace evms::read
