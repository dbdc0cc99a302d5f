// SPDX-License-Identifier: MIT
// Helpers for the job tests: data paths, geometry oracles, running the curvestep binary.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::testing {

inline std::filesystem::path job_data(const std::string& name) { return std::filesystem::path(CURVESTEP_JOBS_TEST_DATA) / name; }
inline std::filesystem::path job_example(const std::string& name) { return std::filesystem::path(CURVESTEP_JOBS_EXAMPLES) / name; }

/// Distance from p to the segment [a, b] (independent of the code under test).
inline double distance_to_segment(const MachinePoint& p, const MachinePoint& a, const MachinePoint& b) {
  double ab2 = 0;
  double apab = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    ab2 += (b[i] - a[i]) * (b[i] - a[i]);
    apab += (p[i] - a[i]) * (b[i] - a[i]);
  }
  const double t = ab2 > 0 ? std::clamp(apab / ab2, 0.0, 1.0) : 0.0;
  double d2 = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double q = a[i] + t * (b[i] - a[i]);
    d2 += (p[i] - q) * (p[i] - q);
  }
  return std::sqrt(d2);
}

/// Distance from p to the polyline (at least one point).
inline double distance_to_polyline(const MachinePoint& p, const std::vector<MachinePoint>& line) {
  if (line.size() == 1) return distance_to_segment(p, line[0], line[0]);
  double best = INFINITY;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) best = std::min(best, distance_to_segment(p, line[i], line[i + 1]));
  return best;
}

inline double distance(const MachinePoint& a, const MachinePoint& b) { return distance_to_segment(a, b, b); }

/// Result of running the binary.
struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// Runs `curvestep <arguments>` (arguments are passed through the shell: quote as needed).
inline RunResult run_curvestep(const std::string& arguments) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path() / ("curvestep_jobs_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto out = dir / ("out" + std::to_string(counter) + ".txt");
  const auto err = dir / ("err" + std::to_string(counter) + ".txt");
  ++counter;
  const std::string command =
      std::string("'") + CURVESTEP_BINARY + "' " + arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_file(out);
  result.err = read_file(err);
  return result;
}

/// Parses "x,y,z" CSV text (header first).
inline std::vector<MachinePoint> parse_points_csv(const std::string& text) {
  std::vector<MachinePoint> points;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "x,y,z");
  while (std::getline(in, line)) {
    MachinePoint p{};
    std::istringstream fields(line);
    std::string field;
    for (std::size_t i = 0; i < 3; ++i) {
      REQUIRE(std::getline(fields, field, ','));
      p[i] = std::stod(field);
    }
    points.push_back(p);
  }
  return points;
}

}  // namespace curvestep::testing
