// SPDX-License-Identifier: MIT
#include "jog_move.hpp"

#include <sstream>

#include <curvestep/host/csv.hpp>

namespace curvestep::host {

Job jog_job(const std::array<double, 3>& start, const std::array<double, 3>& distance, double feed_mm_per_s) {
  std::ostringstream text;
  text << "{\"version\": 1, \"units\": \"mm\", \"segments\": [{\"type\": \"line\", \"points\": [[";
  for (std::size_t a = 0; a < 3; ++a) text << (a == 0 ? "" : ", ") << format_number(start[a]);
  text << "], [";
  for (std::size_t a = 0; a < 3; ++a) text << (a == 0 ? "" : ", ") << format_number(start[a] + distance[a]);
  text << "]]";
  if (feed_mm_per_s > 0) text << ", \"feed\": " << format_number(feed_mm_per_s);
  text << "}]}";
  return parse_job(text.str(), "jog");
}

}  // namespace curvestep::host
