// SPDX-License-Identifier: MIT
// HIL without a planner on the device: the real `curvestep device --fast --executor` (App with
// Lookahead 0, as the STM32F1 executor image) on a pseudo-terminal, driven by `curvestep stream`,
// which plans the job itself and sends pieces; the reference is `curvestep sim` run independently
// on the same files, with the same --lookahead.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;

namespace {

/// `curvestep stream` to `port` with capture; exit status, stdout in `output`, stderr in `errors`.
int stream_to(const std::filesystem::path& job, const std::filesystem::path& machine, const std::string& port,
              const std::filesystem::path& capture, const std::vector<std::string>& extra, std::string& output,
              std::string& errors) {
  std::vector<std::string> arguments{"stream", job.string(), "--machine", machine.string(), "--port", port, "--capture",
                                     capture.string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return ct::run_program(arguments, errors, "stream", std::chrono::seconds(150), &output);
}

/// 40 collinear lines of 0.25 mm: at the feed of 50 mm/s braking takes about 1.6 mm, so the
/// look-ahead window decides the cruise speed.
std::filesystem::path short_lines_job() {
  nlohmann::json segments = nlohmann::json::array();
  for (int k = 0; k < 40; ++k) segments.push_back({{"type", "line"}, {"points", {{0.25 * k, 0.0}, {0.25 * (k + 1), 0.0}}}});
  const auto path = ct::scratch_dir() / "executor_short_lines.json";
  std::ofstream(path) << nlohmann::json({{"version", 1}, {"units", "mm"}, {"segments", segments}}).dump(1);
  return path;
}

}  // namespace

TEST_CASE("hil: every example job streamed to curvestep device --executor gives the setpoints of curvestep sim bit for bit",
          "[integration][hil][pieces]") {
  const auto machine = ct::wire_exact_machine();
  ct::Process device({"device", "--fast", "--executor"}, "executor.stderr");
  const std::string port = device.first_line();
  REQUIRE(port.rfind("/dev/pts/", 0) == 0);
  int jobs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CURVESTEP_EXAMPLE_JOBS)) {
    const auto& path = entry.path();
    if (path.extension() != ".json" || path.filename() == "machine.json") continue;
    INFO("job " << path.filename().string());
    // The example file itself: the host plans it as curvestep sim does, nothing is rounded for the wire.
    const auto expected = ct::simulate_with(path, machine, {}, "executor_" + path.stem().string());
    const auto capture = ct::scratch_dir() / ("executor_" + path.stem().string() + ".csv");
    std::string output;
    std::string errors;
    const int status = stream_to(path, machine, port, capture, {}, output, errors);
    INFO(errors);
    INFO(output);
    REQUIRE(status == 0);
    ct::check_same_setpoints(expected, capture);
    CHECK_THAT(output, Catch::Contains("device look-ahead:   none (it replays pieces planned here with the distance window: "
                                       "curvestep sim gives the same setpoints)"));
    CHECK_THAT(output, Catch::Contains("pieces sent:"));
    ++jobs;
  }
  CHECK(jobs >= 4);
  INFO(device.stderr_text());
  CHECK(device.stop() == 0);
}

TEST_CASE("hil: curvestep stream --lookahead N to an executor gives curvestep sim --lookahead N", "[integration][hil][pieces]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = short_lines_job();
  const auto narrow = ct::simulate_with(job, machine, {"--lookahead", "1"}, "executor_lines_1");
  REQUIRE(ct::first_difference(narrow, ct::simulate_with(job, machine, {}, "executor_lines_16")) != -1);  // the window matters
  ct::Process device({"device", "--fast", "--executor"}, "executor_lookahead.stderr");
  const std::string port = device.first_line();
  const auto capture = ct::scratch_dir() / "executor_lines_1.csv";
  std::string output;
  std::string errors;
  const int status = stream_to(job, machine, port, capture, {"--lookahead", "1"}, output, errors);
  INFO(errors);
  REQUIRE(status == 0);
  ct::check_same_setpoints(narrow, capture);
  CHECK_THAT(output, Catch::Contains("--lookahead 1: curvestep sim --lookahead 1 gives the same setpoints"));
  // Outside 1..16 the command line refuses before connecting.
  const int refused = stream_to(job, machine, port, capture, {"--lookahead", "17"}, output, errors);
  CHECK(refused != 0);
  CHECK_THAT(errors, Catch::Contains("--lookahead"));
  INFO(device.stderr_text());
  CHECK(device.stop() == 0);
}
