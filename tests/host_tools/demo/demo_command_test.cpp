// SPDX-License-Identifier: MIT
// `curvestep demo --out DIR`: the real program streams both bundled jobs to a virtual device and
// must report every captured setpoint identical to the simulator's, and write its plots, setpoint
// CSVs and reports (non-empty, of the right kind) for both.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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

}  // namespace

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
