// SPDX-License-Identifier: MIT
// Every example job (examples/jobs/*.json, loaded as the simulator loads them) runs with chunked
// interpolation within chunk_error_bound of the exact per-tick evaluation, on the example machine
// and at 10 kHz, in double and Q16.16.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "chunk_test_support.hpp"

#ifdef CURVESTEP_MOTION_EXAMPLE_JOBS
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

using namespace curvestep;
using namespace curvestep::testing;

TEST_CASE("motion: every example job stays within chunk_error_bound of the exact per-tick evaluation", "[core][motion][chunks]") {
  const std::filesystem::path folder = CURVESTEP_MOTION_EXAMPLE_JOBS;
  const MachineLimits example = host::load_machine(folder / "machine.json");
  MachineLimits fast = example;
  fast.rate_hz = 10000;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "machine.json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 4);
  for (const auto& file : files) {
    const auto job = host::load_job(file);
    for (const MachineLimits& m : {example, fast}) {
      INFO(file.filename().string() << " at " << m.rate_hz << " Hz");
      const auto stepped = run_chunked<double>(job.segments, m, HermiteChunk::max_ticks);
      const auto exact = run_chunked<double>(job.segments, m, 1);
      const auto c = compare_streams(stepped, exact, m);
      CHECK(c.same_shape);
      CHECK(c.exact_ticks_identical);
      CHECK(c.worst_ratio <= 1.0);
      CHECK(c.worst_position <= 1e-3 * m.tolerance_mm);
      CHECK(stepped.stats.stepped_ticks * 2 > stepped.setpoints.size());
      const auto ps = measure(stepped.setpoints, m.rate_hz);
      const auto pe = measure(exact.setpoints, m.rate_hz);
      const double slack = std::sqrt(3.0) * 1e-3;
      CHECK(ps.acceleration <= pe.acceleration + slack * m.a_max_mm_per_s2);
      CHECK(ps.jerk <= pe.jerk + slack * m.j_max_mm_per_s3);
      INFO(file.filename().string() << " " << m.rate_hz << " Hz: " << stepped.setpoints.size() << " ticks, "
                                    << stepped.stats.exact_evaluations << " exact evaluations, worst "
                                    << c.worst_position << " mm (" << c.worst_ratio << " of the bound)");
      // Q16.16 (what a firmware emits): the same job ends on the same raw point.
      const auto q_stepped = run_chunked<Q16_16>(job.segments, m, HermiteChunk::max_ticks);
      const auto q_exact = run_chunked<Q16_16>(job.segments, m, 1);
      REQUIRE(q_stepped.setpoints.size() == q_exact.setpoints.size());
      CHECK(q_stepped.setpoints.back() == q_exact.setpoints.back());
    }
  }
}
#endif
