// SPDX-License-Identifier: MIT
// `curvestep demo --out DIR`: the real program streams both bundled jobs to a virtual device and
// must report every captured setpoint identical to the simulator's, and write its plots, setpoint
// CSVs and reports (non-empty, of the right kind) for both.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <catch2/catch.hpp>

namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The block of the demo's output that follows the line naming `job`, up to the next job.
std::string block_of(const std::string& out, const std::string& job) {
  const auto start = out.find("  " + job + "\n");
  if (start == std::string::npos) return {};
  const auto end = out.find("\n  ", out.find("identical", start));
  return out.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

/// Runs `curvestep demo ARGS --out DIR/out` in a fresh DIR; the exit status and the output.
struct DemoResult {
  std::filesystem::path dir;
  int status = -1;
  std::string out;
};
DemoResult run_demo(const std::string& arguments) {
  char pattern[] = "/tmp/curvestep_demo_test_XXXXXX";
  REQUIRE(::mkdtemp(pattern) != nullptr);
  DemoResult result;
  result.dir = pattern;
  const std::filesystem::path out_file = result.dir / "stdout.txt";
  const std::string command = std::string(CURVESTEP_BINARY) + " demo " + arguments + " --out " + (result.dir / "out").string() +
                              " >" + out_file.string() + " 2>&1";
  const int raw = std::system(command.c_str());
  result.out = slurp(out_file);
  REQUIRE(WIFEXITED(raw));
  result.status = WEXITSTATUS(raw);
  return result;
}

/// The largest x and y of a setpoint CSV (t,x,y,z,v,index).
std::pair<double, double> max_xy(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  double x_max = -1e9;
  double y_max = -1e9;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string t, x, y;
    std::getline(fields, t, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    x_max = std::max(x_max, std::stod(x));
    y_max = std::max(y_max, std::stod(y));
  }
  return {x_max, y_max};
}

}  // namespace

TEST_CASE("demo: the page and layer options of sim, plot and stream shape the drawing", "[host_tools][demo]") {
  // The bundled drawing's extent is its frame, x 5 .. 195, y 5 .. 135 mm: 190 x 130. Rotated by 90°
  // it is 130 x 190; fit into A4 (210 x 297) minus 10 mm margins, room 190 x 277, the scale is
  // min(190/130, 277/190) = 277/190 = 1.457895, the size 189.526 x 277, centred on (105, 148.5):
  // x 10.237 .. 199.763, y 10 .. 287. The frame's extremes are straight edges, so the motion reaches them,
  // within the machine file's blend_tolerance of 0.01 mm (path smoothing may move the path that far).
  const DemoResult fitted = run_demo("--page a4 --fit --margin 10 --rotate 90");
  INFO(fitted.out);
  CHECK(fitted.status == 0);
  CHECK(fitted.out.find("setpoints identical:  no") == std::string::npos);
  CHECK(fitted.out.find("rotated 90° clockwise") != std::string::npos);
  const auto [x_max, y_max] = max_xy(slurp(fitted.dir / "out" / "curvestep_demo_sim.csv"));
  CHECK(x_max == Approx(199.763).margin(0.0105));
  CHECK(y_max == Approx(287.0).margin(0.0105));
  // The program is not shaped: its setpoints are those of a plain run (page options would refuse it).
  const DemoResult plain = run_demo("");
  CHECK(plain.status == 0);
  CHECK(slurp(fitted.dir / "out" / "cnc_pocket_sim.csv") == slurp(plain.dir / "out" / "cnc_pocket_sim.csv"));
  CHECK(slurp(fitted.dir / "out" / "curvestep_demo_sim.csv") != slurp(plain.dir / "out" / "curvestep_demo_sim.csv"));
  // --layers reaches the drawing: the bundled one has no layer "Text"; the text example has.
  const DemoResult missing = run_demo("--layers Text");
  CHECK(missing.status != 0);
  CHECK(missing.out.find("layers: no layer is labelled \"Text\"") != std::string::npos);
  const DemoResult text = run_demo(std::string("--drawing ") + CURVESTEP_EXAMPLES + "/svg/text_label.svg --layers Text");
  INFO(text.out);
  CHECK(text.status == 0);
  CHECK(text.out.find("  text_label.svg\n") != std::string::npos);
  CHECK(text.out.find("setpoints identical:  no") == std::string::npos);
  for (const auto* result : {&fitted, &plain, &missing, &text}) std::filesystem::remove_all(result->dir);
}

TEST_CASE("demo: both bundled jobs stream identical to the simulator and leave plots and reports", "[host_tools][demo]") {
  char pattern[] = "/tmp/curvestep_demo_test_XXXXXX";
  REQUIRE(::mkdtemp(pattern) != nullptr);
  const std::filesystem::path dir(pattern);
  const std::filesystem::path out_file = dir / "stdout.txt";
  const std::string command = std::string(CURVESTEP_BINARY) + " demo --out " + (dir / "out").string() + " >" +
                              out_file.string() + " 2>&1";
  const int raw = std::system(command.c_str());
  const std::string out = slurp(out_file);
  INFO(out);
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 0);
  for (const std::string job : {"curvestep_demo.svg", "cnc_pocket.ngc"}) {
    INFO(job);
    const std::string block = block_of(out, job);
    REQUIRE_FALSE(block.empty());
    CHECK(block.find("setpoints identical:  yes") != std::string::npos);
    CHECK(block.find("captured of") != std::string::npos);
    CHECK(block.find(" 0 captured") == std::string::npos);
    const std::string stem = std::filesystem::path(job).stem().string();
    for (const std::string suffix : {"_path.svg", "_report.html", "_device.csv", "_sim.csv"}) {
      const auto file = dir / "out" / (stem + suffix);
      INFO(file);
      REQUIRE(std::filesystem::exists(file));
      CHECK(std::filesystem::file_size(file) > 0);
    }
    const std::string plot = slurp(dir / "out" / (stem + "_path.svg"));
    CHECK(plot.find("<svg") != std::string::npos);
    CHECK(plot.find("</svg>") != std::string::npos);
    const std::string report = slurp(dir / "out" / (stem + "_report.html"));
    CHECK(report.find("<html") != std::string::npos);
    CHECK(report.find("</html>") != std::string::npos);
    CHECK(slurp(dir / "out" / (stem + "_device.csv")).rfind("t,x,y,z,v,index\n", 0) == 0);
    CHECK(slurp(dir / "out" / (stem + "_sim.csv")).rfind("t,x,y,z,v,index\n", 0) == 0);
  }
  std::filesystem::remove_all(dir);
}
