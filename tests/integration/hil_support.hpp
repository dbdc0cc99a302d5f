// SPDX-License-Identifier: MIT
// HIL test helpers: wire-exact job and machine files, raw Q16.16 setpoints read from CSV, and
// `curvestep sim`'s setpoints to compare a device's stream with.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <curvestep/host/link/status_query.hpp>
#include <curvestep/host/link/transport.hpp>

#include "process.hpp"

namespace curvestep::test {

/// A machine whose every value travels exactly on the wire (protocol version 2 carries the
/// planning limits as binary64, the rapid speed and the profile too; feeds are Q16.16), with
/// a rapid speed and a tolerance that version 1 could not carry: the device and `curvestep
/// sim` plan from identical numbers.
inline std::filesystem::path wire_exact_machine() {
  const auto path = scratch_dir() / "machine.json";
  std::ofstream(path) << R"({
  "version": 1, "v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "rapid": 150,
  "tolerance": 0.01, "rate_hz": 1000, "junction_deviation": 0.02,
  "max_step_rate": 100000, "profile": "scurve",
  "axes": {
    "x": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000},
    "y": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000},
    "z": {"steps_per_mm": 400, "v_max": 20, "a_max": 500}
  }
})";
  return path;
}

/// A machine with soft limits (jogs, the console): x -50 .. 100, y -50 .. 100, z -10 .. 10 mm.
inline std::filesystem::path travel_machine() {
  const auto path = scratch_dir() / "travel_machine.json";
  std::ofstream(path) << R"({
  "version": 1, "v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "rapid": 150,
  "tolerance": 0.01, "rate_hz": 1000, "junction_deviation": 0.02, "max_step_rate": 100000, "profile": "scurve",
  "axes": {
    "x": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000, "travel": [-50, 100]},
    "y": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000, "travel": [-50, 100]},
    "z": {"steps_per_mm": 400, "v_max": 20, "a_max": 500, "travel": [-10, 10]}
  }
})";
  return path;
}

/// The controller's StatusReport, read over the protocol by a second client (a new session).
inline protocol::StatusReport controller_status(const std::string& port) {
  auto transport = host::link::open_port(port, 115200);
  return host::link::read_status(*transport, protocol::SenderSettings{100, 10, 3000});
}

/// The controller's commanded position, raw Q16.16 (controller_status).
inline std::array<std::int32_t, 3> controller_position(const std::string& port) {
  const protocol::StatusReport report = controller_status(port);
  return {report.position[0], report.position[1], report.position[2]};
}

/// 80 steps/mm on x and y, a trapezoid profile at a = 1000 mm/s^2 (feed 50 mm/s, 1000 Hz), so a
/// test can compute setpoints by hand; `extra` root members are added (e.g. a "homing" section).
inline std::filesystem::path trapezoid_machine(const std::string& name, const std::string& extra = "") {
  const auto path = scratch_dir() / (name + ".json");
  std::ofstream(path) << R"({
  "version": 1, "v_max": 200, "a_max": 1000, "j_max": 50000, "feed": 50, "rapid": 50,
  "tolerance": 0.01, "rate_hz": 1000, "junction_deviation": 0.02, "max_step_rate": 100000, "profile": "trapezoid",
  "axes": {
    "x": {"steps_per_mm": 80, "v_max": 200, "a_max": 1000},
    "y": {"steps_per_mm": 80, "v_max": 200, "a_max": 1000},
    "z": {"steps_per_mm": 400, "v_max": 20, "a_max": 500}
  })" << (extra.empty() ? "" : ",\n  " + extra) << "\n}\n";
  return path;
}

/// A copy of `job` with every weight rounded to Q16.16 (the wire's format), so the file means
/// the same to the simulator and to the device.
inline std::filesystem::path wire_exact_job(const std::filesystem::path& job) {
  std::ifstream in(job);
  nlohmann::json root = nlohmann::json::parse(in, nullptr, true, true);
  for (auto& segment : root.at("segments")) {
    if (!segment.contains("weights")) continue;
    for (auto& w : segment.at("weights")) w = std::nearbyint(w.get<double>() * 65536.0) / 65536.0;
  }
  const auto path = scratch_dir() / ("exact_" + job.filename().string());
  std::ofstream(path) << root.dump(2);
  return path;
}

/// A long 2D job: `count` lines zig-zagging along X (about 10 mm each).
inline std::filesystem::path zigzag_job(int count) {
  nlohmann::json segments = nlohmann::json::array();
  for (int i = 0; i < count; ++i) {
    const double x0 = 4.0 * i;
    const double y0 = (i % 2 == 0) ? 0.0 : 10.0;
    segments.push_back({{"type", "line"}, {"points", {{x0, y0}, {x0 + 4.0, 10.0 - y0}}}});
  }
  const nlohmann::json root = {{"version", 1}, {"units", "mm"}, {"segments", segments}};
  const auto path = scratch_dir() / ("zigzag_" + std::to_string(count) + ".json");
  std::ofstream(path) << root.dump(1);
  return path;
}

/// One setpoint as raw Q16.16 (t as an index-scaled double is compared too).
struct RawSetpoint {
  double t = 0;
  std::array<std::int64_t, 3> raw{};
  std::uint64_t index = 0;  ///< the index column: the setpoint's tick
  friend bool operator==(const RawSetpoint&, const RawSetpoint&) = default;
};

/// Reads `t,x,y,z,v,index` CSV; each coordinate must be an exact Q16.16 value. The index is
/// compared with the other stream's like the coordinates (operator==).
inline std::vector<RawSetpoint> read_raw_setpoints(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error("cannot read " + csv.string());
  std::string line;
  std::getline(in, line);
  if (line != "t,x,y,z,v,index") throw std::runtime_error(csv.string() + ": unexpected header " + line);
  std::vector<RawSetpoint> out;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string field;
    RawSetpoint r;
    std::getline(s, field, ',');
    r.t = std::stod(field);
    for (auto& axis : r.raw) {
      std::getline(s, field, ',');
      const double scaled = std::stod(field) * 65536.0;
      if (scaled != std::nearbyint(scaled)) throw std::runtime_error(csv.string() + ": not a Q16.16 value: " + field);
      axis = static_cast<std::int64_t>(scaled);
    }
    std::getline(s, field, ',');  // v
    std::getline(s, field, ',');
    r.index = std::stoull(field);
    out.push_back(r);
  }
  return out;
}

/// Index of the first differing setpoint, or -1 if equal (sizes included).
inline long first_difference(const std::vector<RawSetpoint>& a, const std::vector<RawSetpoint>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!(a[i] == b[i])) return static_cast<long>(i);
  }
  return a.size() == b.size() ? -1 : static_cast<long>(n);
}

/// Runs `curvestep sim --lookahead 16` (the window of `curvestep device`, App<_, _, 32, 16>) on `job`
/// with `machine` and returns its setpoints (exit status 3, limits exceeded, still writes them).
inline std::vector<RawSetpoint> simulate(const std::filesystem::path& job, const std::filesystem::path& machine) {
  const auto csv = scratch_dir() / ("sim_" + job.stem().string() + ".csv");
  std::string errors;
  const int status =
      run_program({"sim", job.string(), "--machine", machine.string(), "--lookahead", "16", "-o", csv.string()}, errors, "sim");
  INFO(errors);
  REQUIRE((status == 0 || status == 3));
  return read_raw_setpoints(csv);
}

/// `curvestep sim JOB --machine MACHINE [extra...] -o CSV` (exit status 0, or 3: limits exceeded):
/// its setpoints; `tag` names the scratch files.
inline std::vector<RawSetpoint> simulate_with(const std::filesystem::path& job, const std::filesystem::path& machine,
                                              const std::vector<std::string>& extra, const std::string& tag) {
  const auto csv = scratch_dir() / ("sim_" + tag + ".csv");
  std::vector<std::string> arguments{"sim", job.string(), "--machine", machine.string(), "-o", csv.string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  std::string errors;
  const int status = run_program(arguments, errors, "sim_" + tag);
  INFO(errors);
  REQUIRE((status == 0 || status == 3));
  return read_raw_setpoints(csv);
}

/// `curvestep stream JOB --machine MACHINE --port PORT --capture CAPTURE`'s arguments.
inline std::vector<std::string> stream_arguments(const std::filesystem::path& job, const std::filesystem::path& machine,
                                                 const std::string& port, const std::filesystem::path& capture) {
  return {"stream", job.string(), "--machine", machine.string(), "--port", port, "--capture", capture.string()};
}

/// The events of the streamer's replay line "curvestep sim --override-at EVENTS gives" ("0:150:100,1.2:100:100").
inline std::string override_replay(const std::string& output) {
  std::smatch found;
  REQUIRE(std::regex_search(output, found, std::regex("curvestep sim (--override-at [0-9.e:,-]+) gives")));
  return found[1].str().substr(std::string("--override-at ").size());
}

/// T and R of the streamer's replay line "curvestep sim --hold-at T:R gives" (its first hold), as printed.
inline std::array<std::string, 2> hold_replay(const std::string& output) {
  std::smatch found;
  REQUIRE(std::regex_search(output, found, std::regex("curvestep sim --hold-at ([0-9.e-]+):([0-9.e-]+) gives")));
  return {found[1].str(), found[2].str()};
}

/// The setpoints captured in `csv` are `expected`, every one, bit for bit; returns them.
inline std::vector<RawSetpoint> check_same_setpoints(const std::vector<RawSetpoint>& expected, const std::filesystem::path& csv) {
  auto actual = read_raw_setpoints(csv);
  CHECK(actual.size() == expected.size());
  CHECK(first_difference(expected, actual) == -1);
  return actual;
}

/// Streams `job` with `curvestep stream [extra...]` to a `curvestep device` started with
/// `device_options`, requires success and `expected`'s setpoints bit for bit in the capture;
/// returns the device's standard error (stopped, exit 0 checked) and the stream's output.
inline std::string stream_to_new_device(const std::filesystem::path& job, const std::filesystem::path& machine,
                                        const std::vector<std::string>& device_options, const std::string& tag,
                                        const std::vector<RawSetpoint>& expected, std::string& output,
                                        const std::vector<std::string>& extra = {}) {
  Process device(device_options, tag + ".stderr");
  const std::string port = device.first_line();
  REQUIRE(port.rfind("/dev/pts/", 0) == 0);
  const auto capture = scratch_dir() / (tag + ".csv");
  std::vector<std::string> arguments{"stream", job.string(), "--machine", machine.string(), "--port", port, "--capture",
                                     capture.string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  std::string errors;
  const int status = run_program(arguments, errors, "stream", std::chrono::seconds(150), &output);
  INFO(errors);
  INFO(output);
  REQUIRE(status == 0);
  check_same_setpoints(expected, capture);
  CHECK(device.stop() == 0);
  return device.stderr_text();
}

}  // namespace curvestep::test
