// SPDX-License-Identifier: MIT
// HIL: the real `curvestep device --fast` on a pseudo-terminal, driven by `curvestep stream`,
// against `curvestep sim` run independently on the same job and machine files.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using namespace std::chrono_literals;

namespace {

/// Runs `curvestep stream` to `port`; returns its exit status, stderr in `errors` (stdout in `output`).
int stream(const std::filesystem::path& job, const std::filesystem::path& machine, const std::string& port,
           const std::filesystem::path& capture, std::string& errors, const std::vector<std::string>& extra = {},
           std::string* output = nullptr) {
  std::vector<std::string> arguments{"stream", job.string(), "--machine", machine.string(), "--port", port, "--capture",
                                     capture.string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return ct::run_program(arguments, errors, "stream", std::chrono::seconds(150), output);
}

bool has_turns(const std::filesystem::path& job) {
  std::ifstream in(job);
  const auto root = nlohmann::json::parse(in, nullptr, true, true);
  for (const auto& s : root.at("segments")) {
    if (s.contains("turns") && s.at("turns").get<int>() > 0) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("hil: every example job streamed to curvestep device gives the setpoints of curvestep sim bit for bit",
          "[integration][hil]") {
  const auto machine = ct::wire_exact_machine();
  ct::Process device({"device", "--fast"}, "device.stderr");
  const std::string port = device.first_line();
  REQUIRE(port.rfind("/dev/pts/", 0) == 0);
  int jobs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CURVESTEP_EXAMPLE_JOBS)) {
    const auto& path = entry.path();
    if (path.extension() != ".json" || path.filename() == "machine.json") continue;
    const auto job = ct::wire_exact_job(path);
    INFO("job " << path.filename().string());
    const auto expected = ct::simulate(job, machine);
    const auto capture = ct::scratch_dir() / ("device_" + path.stem().string() + ".csv");
    std::string errors;
    const int status = stream(job, machine, port, capture, errors);
    INFO(errors);
    REQUIRE(status == 0);
    ct::check_same_setpoints(expected, capture);
    ++jobs;
  }
  CHECK(jobs >= 4);
  INFO(device.stderr_text());
  CHECK(device.stop() == 0);
}

TEST_CASE("hil: a long job of many segments runs with the queue topped up and matches curvestep sim", "[integration][hil]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(120);
  const auto expected = ct::simulate(job, machine);
  ct::Process device({"device", "--fast"}, "device_long.stderr");
  const std::string port = device.first_line();
  const auto capture = ct::scratch_dir() / "device_long.csv";
  std::string errors;
  REQUIRE(stream(job, machine, port, capture, errors) == 0);
  ct::check_same_setpoints(expected, capture);
}

TEST_CASE("hil: a helix of several turns streams as one arc and matches curvestep sim bit for bit",
          "[integration][hil]") {
  const auto machine = ct::wire_exact_machine();
  ct::Process device({"device", "--fast"}, "device_turns.stderr");
  const std::string port = device.first_line();
  std::string errors;
  const auto job = std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / "helix.json";
  REQUIRE(has_turns(job));
  const auto expected = ct::simulate(job, machine);
  const auto capture = ct::scratch_dir() / "helix.csv";
  const int status = stream(job, machine, port, capture, errors);
  INFO(errors);
  REQUIRE(status == 0);
  const auto actual = ct::check_same_setpoints(expected, capture);
  // two turns rising 5 mm: the stream ends where it started in XY, 5 mm up
  REQUIRE(!actual.empty());
  CHECK(actual.back().raw == std::array<std::int64_t, 3>{10 * 65536, 0, 5 * 65536});
}

TEST_CASE("hil: with 1 percent corrupted and 1 percent dropped bytes to the device the job completes bit-identical",
          "[integration][hil][faults]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::wire_exact_job(std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / "every_type.json");
  const auto expected = ct::simulate(job, machine);
  ct::Process device({"device", "--fast"}, "device_faults.stderr");
  const std::string device_port = device.first_line();
  ct::Process proxy({"proxy", "--device", device_port, "--corrupt", "0.01", "--drop", "0.01", "--duplicate", "0.005",
                     "--delay", "0.005", "--delay-ms", "5", "--seed", "7", "--direction", "to-device"},
                    "proxy_faults.stderr");
  const std::string port = proxy.first_line();
  const auto capture = ct::scratch_dir() / "device_faults.csv";
  std::string errors;
  const int status = stream(job, machine, port, capture, errors);
  INFO(errors);
  REQUIRE(status == 0);
  ct::check_same_setpoints(expected, capture);
  proxy.stop();
  INFO(proxy.stderr_text());
  CHECK_THAT(proxy.stderr_text(), !Catch::Contains("corrupted 0,") && !Catch::Contains("dropped 0,"));
}

TEST_CASE("hil: with 1 percent corrupted and 1 percent dropped bytes in both directions every setpoint arrives once and bit-identical",
          "[integration][hil][faults]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(40);
  const auto expected = ct::simulate(job, machine);
  ct::Process device({"device", "--fast"}, "device_both.stderr");
  const std::string device_port = device.first_line();
  ct::Process proxy({"proxy", "--device", device_port, "--corrupt", "0.01", "--drop", "0.01", "--seed", "11"},
                    "proxy_both.stderr");
  const std::string port = proxy.first_line();
  const auto capture = ct::scratch_dir() / "device_both.csv";
  std::string errors;
  std::string output;
  const int status = stream(job, machine, port, capture, errors, {}, &output);
  INFO(errors);
  INFO(output);
  REQUIRE(status == 0);
  // None lost, none duplicated, every one equal to the simulator's at the same index.
  ct::check_same_setpoints(expected, capture);
  CHECK_THAT(output, Catch::Contains("ticks standing:      0 ") && Catch::Contains("setpoints duplicated: 0"));
  // The faults reached the host: frames from the controller were damaged (and resent).
  CHECK_THAT(output, !Catch::Contains("damaged frames:      0\n"));
  proxy.stop();
  INFO(proxy.stderr_text());
  CHECK_THAT(proxy.stderr_text(), !Catch::Contains("corrupted 0,") && !Catch::Contains("dropped 0,"));
  const std::string finished = "idle at tick " + std::to_string(expected.size() - 1);
  std::string log;
  for (int i = 0; i < 100 && log.find(finished) == std::string::npos; ++i) {
    std::this_thread::sleep_for(20ms);
    log = device.stderr_text();
  }
  CHECK_THAT(log, Catch::Contains(finished));
}

TEST_CASE("hil: when the link dies mid-job the device holds and says so and the host exits with a clear error",
          "[integration][hil][faults]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(200);
  ct::Process device({"device", "--fast", "--link-timeout-ms", "500"}, "device_cut.stderr");
  const std::string device_port = device.first_line();
  ct::Process proxy({"proxy", "--device", device_port, "--cut-after-bytes", "1500"}, "proxy_cut.stderr");
  const std::string port = proxy.first_line();
  std::string errors;
  const auto started = std::chrono::steady_clock::now();
  const int status = stream(job, machine, port, ct::scratch_dir() / "cut.csv", errors, {"--link-timeout-ms", "1500"});
  CHECK(std::chrono::steady_clock::now() - started < 20s);
  CHECK(status == 4);
  CHECK_THAT(errors, Catch::Contains("link failed") && Catch::Contains("LinkTimeout"));
  std::string log;
  for (int i = 0; i < 100 && log.find("holding") == std::string::npos; ++i) {
    std::this_thread::sleep_for(50ms);
    log = device.stderr_text();
  }
  INFO(log);
  CHECK_THAT(log, Catch::Contains("holding") && Catch::Contains("LinkTimeout"));
}
