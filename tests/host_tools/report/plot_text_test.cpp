// SPDX-License-Identifier: MIT
// The plot's text (job name, title) with control characters or invalid UTF-8 stays well-formed XML
// (issue 19 item 9).
#include <string>

#include <catch2/catch.hpp>
#include <tinyxml2.h>

#include <curvestep/host/job.hpp>
#include <curvestep/host/report.hpp>

using namespace curvestep::host;

namespace {

/// True if `text` has a byte XML 1.0 forbids (C0 controls other than tab, LF, CR) or a byte that is
/// never valid in UTF-8 (0xc0, 0xc1, 0xf5..0xff) - an independent, coarser check than printable().
bool has_forbidden_bytes(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') return true;
    if (byte == 0xc0 || byte == 0xc1 || byte >= 0xf5) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("plot: a job name with control characters and invalid UTF-8 gives well-formed SVG", "[host_tools][report][messages]") {
  const std::string name = std::string("evil\x1b[2J\x01\xff name <&>.json");
  const Job job = parse_job(R"({"version": 1, "segments": [{"type": "line", "points": [[0, 0], [10, 0]]}]})", name);
  for (const std::string& title : {std::string(), std::string("title\x07\xfe")}) {
    PathPlotOptions options;
    options.title = title;
    const std::string svg = path_plot_svg(job, nullptr, options);
    CHECK_FALSE(has_forbidden_bytes(svg));
    tinyxml2::XMLDocument doc;
    REQUIRE(doc.Parse(svg.c_str(), svg.size()) == tinyxml2::XML_SUCCESS);
    const tinyxml2::XMLElement* title_element = doc.RootElement()->FirstChildElement("title");
    REQUIRE(title_element != nullptr);
    const std::string shown = title_element->GetText();
    CHECK_THAT(shown, Catch::Contains(title.empty() ? "evil\\x1b[2J\\x01\\xff name <&>.json" : "title\\x07\\xfe"));
  }
}
