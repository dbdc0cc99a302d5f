// SPDX-License-Identifier: MIT
// Plotter pen up/down: the machine file's "pen" section and the z moves it adds to an SVG job,
// expected segments and events worked out by hand.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/pen_moves.hpp>
#include <curvestep/host/svg_import.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

const std::filesystem::path source_dir(CURVESTEP_SOURCE_DIR);

/// Two subpaths on a 100 mm page (user unit 1 mm, machine y = 100 - user y): (10,90)->(20,90) and (30,80)->(40,80).
const char* const two_strokes =
    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\">"
    "<path d=\"M 10 10 L 20 10 M 30 20 L 40 20\"/></svg>\n";

std::string machine_with_pen(const std::string& pen) {
  return R"({"v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "tolerance": 0.01, "rate_hz": 1000, "pen": )" + pen + "}";
}

MachinePoint p(double x, double y, double z) { return MachinePoint{{x, y, z}}; }

void check_line(const Job& job, std::size_t k, bool rapid, const MachinePoint& from, const MachinePoint& to, double feed = -1) {
  INFO("segment " << k);
  REQUIRE(k < job.segments.size());
  CHECK(job.segments[k].kind() == SegmentKind::Line);
  CHECK(job.segments[k].rapid() == rapid);
  CHECK(job.segments[k].start() == from);
  CHECK(job.segments[k].end() == to);
  if (feed >= 0) CHECK(job.segments[k].feed_mm_per_s() == feed);
}

void check_event(const Job& job, std::size_t i, JobEventKind kind, std::size_t before) {
  INFO("event " << i);
  REQUIRE(i < job.events.size());
  CHECK(job.events[i].kind == kind);
  CHECK(job.events[i].before_segment == before);
}

std::string run(const std::string& command, int* status) {
  std::FILE* pipe = popen((std::string(CURVESTEP_BINARY) + " " + command + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string text;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) text += buffer.data();
  const int raw = pclose(pipe);
  *status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return text;
}

}  // namespace

TEST_CASE("pen: the machine file's pen section is read and checked, naming the field", "[host][pipeline][pen]") {
  const MachineFile file = parse_machine_file(machine_with_pen(R"({"axis": "z", "up": 5, "down": 0.1, "feed": 20})"), "m.json");
  REQUIRE(file.pen.has_value());
  CHECK(file.pen->up_mm == 5);
  CHECK(file.pen->down_mm == 6554.0 / 65536);  // 0.1 mm on the Q16.16 grid: 6553.6 -> 6554
  CHECK(file.pen->feed_mm_per_s == 20);
  CHECK_FALSE(load_machine_file(source_dir / "examples/jobs/machine.json").pen.has_value());
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": 2, "down": 2, "feed": 20})"), "m.json"),
                    Catch::Contains("\"pen\".\"down\"") && Catch::Contains("equals \"up\""));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": 40000, "down": 0, "feed": 20})"), "m.json"),
                    Catch::Contains("\"pen\".\"up\"") && Catch::Contains("outside the Q16.16 range"));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": 5, "down": 0, "feed": 0})"), "m.json"),
                    Catch::Contains("\"pen\".\"feed\""));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": 5, "down": 0, "feed": -3})"), "m.json"),
                    Catch::Contains("\"pen\".\"feed\""));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": 5, "down": 0})"), "m.json"), Catch::Contains("feed"));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"axis": "a", "up": 5, "down": 0, "feed": 20})"), "m.json"),
                    Catch::Contains("\"pen\".\"axis\"") && Catch::Contains("servo"));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": "high", "down": 0, "feed": 20})"), "m.json"),
                    Catch::Contains("\"pen\".\"up\""));
  CHECK_THROWS_WITH(parse_machine_file(machine_with_pen(R"({"up": 5, "down": 0, "feed": 20, "servo": 1})"), "m.json"),
                    Catch::Contains("unknown key"));
}

TEST_CASE("pen: a two-subpath drawing gets exactly the hand-expected z moves and pen events", "[host][pipeline][pen]") {
  const Job drawing = parse_svg_job(two_strokes, "two.svg");
  REQUIRE(drawing.segments.size() == 4);  // rapid, line, rapid, line
  PenModel pen;
  pen.up_mm = 2.5;
  pen.down_mm = -1;
  pen.feed_mm_per_s = 20;
  PenMovesReport report;
  const Job job = add_pen_moves(drawing, pen, &report);
  // The machine stands at (0,0,0): lift, travel at 2.5, lower, draw at -1, and so on; ends lifted.
  REQUIRE(job.segments.size() == 9);
  check_line(job, 0, true, p(0, 0, 0), p(0, 0, 2.5));
  check_line(job, 1, true, p(0, 0, 2.5), p(10, 90, 2.5));
  check_line(job, 2, false, p(10, 90, 2.5), p(10, 90, -1), 20);
  check_line(job, 3, false, p(10, 90, -1), p(20, 90, -1), 0);
  check_line(job, 4, true, p(20, 90, -1), p(20, 90, 2.5));
  check_line(job, 5, true, p(20, 90, 2.5), p(30, 80, 2.5));
  check_line(job, 6, false, p(30, 80, 2.5), p(30, 80, -1), 20);
  check_line(job, 7, false, p(30, 80, -1), p(40, 80, -1), 0);
  check_line(job, 8, true, p(40, 80, -1), p(40, 80, 2.5));
  REQUIRE(job.events.size() == 5);
  check_event(job, 0, JobEventKind::PenUp, 0);
  check_event(job, 1, JobEventKind::PenDown, 3);  // after the move down, before drawing
  check_event(job, 2, JobEventKind::PenUp, 4);
  check_event(job, 3, JobEventKind::PenDown, 7);
  check_event(job, 4, JobEventKind::PenUp, 8);
  CHECK(report.lifts == 3);
  CHECK(report.lowers == 2);
  // One source per segment, with the z the segment has.
  REQUIRE(job.sources.size() == 9);
  CHECK(job.sources[3].points.back() == p(20, 90, -1));
  CHECK(job.sources[2].type == SegmentType::Line);
  CHECK(job.sources[4].type == SegmentType::Rapid);
}

TEST_CASE("pen: a servo pen keeps the path and moves by events, each followed by its settle dwell", "[host][pipeline][pen]") {
  const Job drawing = parse_svg_job(two_strokes, "two.svg");
  REQUIRE(drawing.segments.size() == 4);  // rapid, line, rapid, line
  PenModel pen;
  pen.servo = true;
  pen.line = "GPIO18";
  pen.up_pulse_us = 1000.4;  // carried in whole microseconds
  pen.down_pulse_us = 1999.6;
  pen.settle_s = 0.25;
  const Job job = add_pen_moves(drawing, pen);
  // No z moves: the same four segments, bit for bit.
  REQUIRE(job.segments.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(job.segments[k].start() == drawing.segments[k].start());
    CHECK(job.segments[k].end() == drawing.segments[k].end());
  }
  // Up (unknown at the start) before the first travel, down before each stroke, up after it.
  const std::vector<std::pair<JobEventKind, std::size_t>> expected{
      {JobEventKind::PenUp, 0},   {JobEventKind::Dwell, 0}, {JobEventKind::PenDown, 1}, {JobEventKind::Dwell, 1},
      {JobEventKind::PenUp, 2},   {JobEventKind::Dwell, 2}, {JobEventKind::PenDown, 3}, {JobEventKind::Dwell, 3},
      {JobEventKind::PenUp, 4},   {JobEventKind::Dwell, 4}};
  REQUIRE(job.events.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    check_event(job, i, expected[i].first, expected[i].second);
    if (expected[i].first == JobEventKind::Dwell) CHECK(job.events[i].value == 0.25);
    if (expected[i].first == JobEventKind::PenUp) CHECK(job.events[i].value == 1000);    // the servo's width, rounded
    if (expected[i].first == JobEventKind::PenDown) CHECK(job.events[i].value == 2000);
  }
}

TEST_CASE("pen: the machine file's servo pen section, and what it refuses", "[host][pipeline][pen]") {
  const auto load = [](const std::string& pen) {
    const auto path = std::filesystem::temp_directory_path() / ("servo_pen_" + std::to_string(getpid()) + ".json");
    std::ofstream(path) << machine_with_pen(pen);
    return load_machine_file(path);
  };
  const MachineFile file = load(R"({"axis": "servo", "line": "GPIO18", "up_pulse_us": 1000, "down_pulse_us": 2000, "settle": 0.15})");
  REQUIRE(file.pen.has_value());
  CHECK(file.pen->servo);
  CHECK(file.pen->line == "GPIO18");
  CHECK(file.pen->up_pulse_us == 1000);
  CHECK(file.pen->down_pulse_us == 2000);
  CHECK(file.pen->settle_s == 0.15);
  const auto refused = [&](const std::string& pen, const std::string& what) {
    INFO(pen);
    try {
      (void)load(pen);
      FAIL("accepted");
    } catch (const LoadError& e) {
      CHECK_THAT(e.what(), Catch::Contains(what));
    }
  };
  refused(R"({"axis": "servo", "line": "GPIO18", "up_pulse_us": 1000, "down_pulse_us": 1000, "settle": 0.1})", "equals");
  refused(R"({"axis": "servo", "line": "GPIO18", "up_pulse_us": 100, "down_pulse_us": 2000, "settle": 0.1})", "outside 500 .. 2500");
  refused(R"({"axis": "servo", "line": "GPIO18", "up_pulse_us": 1000, "down_pulse_us": 2000, "settle": 11})", "outside 0 .. 10");
  refused(R"({"axis": "servo", "line": "", "up_pulse_us": 1000, "down_pulse_us": 2000, "settle": 0.1})", "empty");
  refused(R"({"axis": "servo", "up_pulse_us": 1000, "down_pulse_us": 2000, "settle": 0.1})", "line");
  refused(R"({"axis": "x", "up": 1, "down": 0, "feed": 5})", "unsupported pen axis");
}

TEST_CASE("pen: a layer change lifts the pen even without travel, and a first stroke at the start comes down", "[host][pipeline][pen]") {
  // Layer A draws from the start point, the machine origin (user (0,100)), to (10,0); layer B goes
  // on from there to (20,0): no travel anywhere.
  const std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" width=\"100mm\" "
      "height=\"100mm\" viewBox=\"0 0 100 100\">"
      "<g inkscape:groupmode=\"layer\" inkscape:label=\"A\"><path d=\"M 0 100 L 10 100\"/></g>"
      "<g inkscape:groupmode=\"layer\" inkscape:label=\"B\"><path d=\"M 10 100 L 20 100\"/></g></svg>\n";
  const Job drawing = parse_svg_job(svg, "ab.svg");
  REQUIRE(drawing.segments.size() == 2);  // no travel at all
  REQUIRE(drawing.events.size() == 1);
  PenModel pen;
  pen.up_mm = 3;
  pen.down_mm = 0;
  pen.feed_mm_per_s = 10;
  const Job job = add_pen_moves(drawing, pen);
  // The start z is already 0 = down: no move, but the pen is said to come down. At the layer
  // change: up, the pause, down again, then B; the end lifts.
  REQUIRE(job.segments.size() == 5);
  check_line(job, 0, false, p(0, 0, 0), p(10, 0, 0));
  check_line(job, 1, true, p(10, 0, 0), p(10, 0, 3));
  check_line(job, 2, false, p(10, 0, 3), p(10, 0, 0), 10);
  check_line(job, 3, false, p(10, 0, 0), p(20, 0, 0));
  check_line(job, 4, true, p(20, 0, 0), p(20, 0, 3));
  REQUIRE(job.events.size() == 5);
  check_event(job, 0, JobEventKind::PenDown, 0);
  check_event(job, 1, JobEventKind::PenUp, 1);
  check_event(job, 2, JobEventKind::LayerChange, 2);
  CHECK(job.events[2].text == "B");
  check_event(job, 3, JobEventKind::PenDown, 3);
  check_event(job, 4, JobEventKind::PenUp, 4);
}

TEST_CASE("pen: prepare_job adds the pen moves to SVG jobs only, before smoothing", "[host][pipeline][pen]") {
  const MachineFile plotter = load_machine_file(source_dir / "examples/machines/plotter.json");
  REQUIRE(plotter.pen.has_value());
  const std::filesystem::path svg = std::filesystem::temp_directory_path() / ("curvestep_pen_two_strokes_" + std::to_string(::getpid()) + ".svg");
  {
    std::ofstream out(svg);
    out << two_strokes;
  }
  const PreparedJob prepared = prepare_job(svg, plotter.limits, plotter.blend_tolerance_mm, JobPipelineOptions{}, plotter.pen);
  std::filesystem::remove(svg);
  CHECK(prepared.job.segments.size() == 9);  // smoothing has nothing to blend: every corner is a stop
  CHECK(prepared.job.events.size() == 5);
  CHECK(prepared.job.segments[0].end() == p(0, 0, 3));
  // A JSON job is not plotter art: unchanged.
  const PreparedJob json = prepare_job(source_dir / "examples/jobs/polyline.json", plotter.limits, 0, JobPipelineOptions{}, plotter.pen);
  const PreparedJob plain = prepare_job(source_dir / "examples/jobs/polyline.json", plotter.limits, 0, JobPipelineOptions{});
  CHECK(json.job.segments.size() == plain.job.segments.size());
  CHECK(json.job.events.size() == plain.job.events.size());
}

TEST_CASE("pen: curvestep sim runs the demo drawing on the plotter machine within its limits", "[host][pipeline][pen]") {
  int status = -1;
  const std::string out = run("sim " + (source_dir / "examples/svg/curvestep_demo.svg").string() + " -m " +
                                  (source_dir / "examples/machines/plotter.json").string(),
                              &status);
  INFO(out);
  CHECK(status == 0);
  CHECK(out.find("limit violations:    none") != std::string::npos);
  CHECK(out.find("pen up 11 times, pen down 10 times") != std::string::npos);
  CHECK(out.find("note: pen: ") != std::string::npos);
}

TEST_CASE("pen: curvestep sim names the layer at each layer change, with --layers selecting", "[host][pipeline][pen]") {
  const std::filesystem::path svg = std::filesystem::temp_directory_path() / ("curvestep_pen_layers_" + std::to_string(::getpid()) + ".svg");
  {
    std::ofstream out(svg);
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" "
           "width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\">\n"
           "<g inkscape:groupmode=\"layer\" inkscape:label=\"Red\"><path d=\"M 10 10 L 20 10\"/></g>\n"
           "<g inkscape:groupmode=\"layer\" inkscape:label=\"Blue\"><path d=\"M 30 10 L 40 10\"/></g>\n</svg>\n";
  }
  const std::string machine = (source_dir / "examples/machines/plotter.json").string();
  int status = -1;
  const std::string both = run("sim " + svg.string() + " -m " + machine, &status);
  CHECK(status == 0);
  // Red: up 0, travel 1, down 2, draw 3; up 4, the change, travel 5, down 6, draw 7, up 8.
  CHECK(both.find("layer change (Blue) before segment 5") != std::string::npos);
  const std::string blue = run("sim " + svg.string() + " -m " + machine + " --layers Blue", &status);
  CHECK(status == 0);
  CHECK(blue.find("layer change") == std::string::npos);
  const std::string green = run("sim " + svg.string() + " -m " + machine + " --layers Green,Red", &status);
  std::filesystem::remove(svg);
  CHECK(status != 0);
  CHECK(green.find("no layer is labelled \"Green\" (the layers are \"Red\", \"Blue\")") != std::string::npos);
}
