// SPDX-License-Identifier: MIT
// The HTML report opened in headless Chromium: its script runs without console errors, and its
// screenshot is a real drawing, not a blank page. Every browser run is wrapped in `timeout` and the
// suite has a CTest TIMEOUT, so a stuck browser cannot hang CI.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "report_test_support.hpp"

namespace {

using report_test::run_curvestep;
using report_test::scratch;
using report_test::source;

const char* chromium() {
  const char* configured = std::getenv("CURVESTEP_CHROMIUM");
  return configured != nullptr ? configured : "/usr/bin/chromium";
}

/// Runs headless Chromium on a local file with a new, empty profile; `mode` is --dump-dom or --screenshot=...
report_test::Run run_chromium(const std::string& file, const std::string& mode) {
  char profile_template[] = "/tmp/curvestep_report_chromium_XXXXXX";
  const char* profile = mkdtemp(profile_template);
  REQUIRE(profile != nullptr);
  const std::string command = std::string("timeout -k 5 90 ") + chromium() +
                              " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
                              " --disable-component-update --disable-sync --hide-scrollbars --window-size=900,2200"
                              " --enable-logging=stderr --v=0 --user-data-dir=" + profile + " " + mode + " file://" + file;
  auto r = report_test::run_command(command);
  std::filesystem::remove_all(profile);
  return r;
}

/// Console output of the page (Chromium logs console messages and uncaught exceptions as CONSOLE lines).
bool console_errors(const std::string& log) {
  return log.find(":CONSOLE") != std::string::npos || log.find("Uncaught") != std::string::npos;
}

std::uint32_t big_endian(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

/// Width and height of a PNG (from its IHDR chunk), or {0, 0} if the bytes are not a PNG.
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& png) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  if (png.size() < 24 || png.compare(0, 8, signature) != 0 || png.compare(12, 4, "IHDR") != 0) return {0, 0};
  return {big_endian(png, 16), big_endian(png, 20)};
}

std::string report_file() {
  const std::string html = scratch("chromium_report.html");
  std::remove(html.c_str());
  const auto r = run_curvestep("sim " + source("examples/jobs/every_type.json") + " --machine " + source("examples/jobs/machine.json") +
                           " --report " + html);
  INFO(r.output);
  REQUIRE(r.status == 0);
  return html;
}

}  // namespace

TEST_CASE("report: in headless Chromium the page's script runs and no console error appears", "[host_tools][report]") {
  REQUIRE(std::filesystem::exists(chromium()));  // scripts/install-deps.sh installs chromium
  const std::string html = report_file();
  const auto dom = run_chromium(html, "--dump-dom");
  INFO(dom.output.substr(0, 4000));
  REQUIRE(dom.status == 0);
  CHECK(dom.output.find("data-drawings=\"4\">report rendered: 4 drawings</p>") != std::string::npos);
  CHECK_FALSE(console_errors(dom.output));

  // The check can fail: a page with a script error is caught.
  const std::string broken = scratch("chromium_broken.html");
  std::ofstream(broken) << "<!DOCTYPE html><html><body><p>x</p><script>no_such_function();</script></body></html>\n";
  const auto bad = run_chromium(broken, "--dump-dom");
  CHECK(console_errors(bad.output));
}

TEST_CASE("report: the headless Chromium screenshot of the report is not blank", "[host_tools][report]") {
  REQUIRE(std::filesystem::exists(chromium()));
  const std::string html = report_file();
  const std::string shot = scratch("chromium_report.png");
  std::remove(shot.c_str());
  const auto r = run_chromium(html, "--screenshot=" + shot);
  INFO(r.output.substr(0, 4000));
  REQUIRE(r.status == 0);
  CHECK_FALSE(console_errors(r.output));
  const std::string png = report_test::read_file(shot);
  const auto size = png_size(png);
  CHECK(size.first == 900);
  CHECK(size.second == 2200);

  // A blank page of the same size compresses to almost nothing; the drawings do not.
  const std::string blank_html = scratch("chromium_blank.html");
  std::ofstream(blank_html) << "<!DOCTYPE html><html><body></body></html>\n";
  const std::string blank_shot = scratch("chromium_blank.png");
  std::remove(blank_shot.c_str());
  REQUIRE(run_chromium(blank_html, "--screenshot=" + blank_shot).status == 0);
  const std::string blank = report_test::read_file(blank_shot);
  CHECK(png_size(blank) == size);
  INFO("report PNG " << png.size() << " bytes, blank PNG " << blank.size() << " bytes");
  CHECK(png.size() > 10 * blank.size());
  CHECK(png.size() > 20000);
}
