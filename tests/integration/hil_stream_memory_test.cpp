// SPDX-License-Identifier: MIT
// Memory of `curvestep stream` (issue 19, item 7): a G-code program is not held while it is
// uploaded to a real `curvestep device` on a pty. The file is read for the plan, once more for the
// wire's checks (or, for a controller without a planner, the host's planning) and again as the
// segments go out (streamed_job.hpp, readable_job.hpp). Two programs of 2 000 and 22 000 moves of
// 0.5 mm, every corner a stop (--blend-tolerance 0: one smoothed segment per move), are streamed
// to a device with a planner and to an executor; the stream's largest resident size (wait4) may
// grow by at most 100 bytes a move. The job held whole (the stream of commit 2f8e7c3, and
// `--optimize` still) took about 750 bytes a move more: 7.5 -> 37.7 MB for 2 000 -> 42 000 moves.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "hil_support.hpp"
#include "process.hpp"
#include "support/child_peak_memory.hpp"

namespace ct = curvestep::test;

namespace {

/// A zig-zag of `moves` moves of 0.5 mm, alternately along x and y, at 200 mm/s.
std::filesystem::path write_zigzag_program(const std::string& name, int moves) {
  const auto path = ct::scratch_dir() / name;
  std::ofstream out(path);
  out << "G21 G90 G17\nF12000\nG0 X0 Y0\n";
  double x = 0, y = 0;
  for (int i = 0; i < moves; ++i) {
    if (i % 2 == 0) {
      x += 0.5;
    } else {
      y = y == 0 ? 0.5 : 0.0;
    }
    out << "G1 X" << x << " Y" << y << "\n";
  }
  out << "M2\n";
  return path;
}

/// The stream's peak resident size in KiB for `program` uploaded to a new `curvestep device`.
long stream_peak_kib(const std::filesystem::path& program, const std::vector<std::string>& device_options, const std::string& tag) {
  ct::Process device(device_options, tag + ".stderr");
  const std::string port = device.first_line();
  REQUIRE(port.rfind("/dev/pts/", 0) == 0);
  const long kib = curvestep::testing::peak_resident_kib({CURVESTEP_PROGRAM, "stream", program.string(), "--machine",
                                                           std::string(CURVESTEP_EXAMPLE_JOBS) + "/machine.json", "--port", port,
                                                           "--blend-tolerance", "0"});
  CHECK(device.stop() == 0);
  return kib;
}

}  // namespace

TEST_CASE("memory: curvestep stream of a G-code program 20 000 moves longer costs at most 100 bytes a move more",
          "[integration][hil][memory]") {
  const auto short_program = write_zigzag_program("memory_short.ngc", 2'000);
  const auto long_program = write_zigzag_program("memory_long.ngc", 22'000);
  constexpr long margin_kib = 20'000 * 100 / 1024;
  for (const bool executor : {false, true}) {
    std::vector<std::string> device{"device", "--fast"};
    if (executor) device.push_back("--executor");
    const std::string tag = executor ? "memory_executor" : "memory_planner";
    const long short_kib = stream_peak_kib(short_program, device, tag + "_short");
    const long long_kib = stream_peak_kib(long_program, device, tag + "_long");
    INFO((executor ? "executor" : "device with a planner") << ": " << short_kib << " KiB for 2 000 moves, " << long_kib
                                                          << " KiB for 22 000");
    CHECK(long_kib <= short_kib + margin_kib);
  }
  std::filesystem::remove(short_program);
  std::filesystem::remove(long_program);
}
