// SPDX-License-Identifier: MIT
// jog_job: a relative straight move as a one-line job (what `curvestep jog` and `curvestep home`
// send; the controller plans it with the machine's limits like any job).
#pragma once

#include <array>

#include <curvestep/host/job.hpp>

namespace curvestep::host {

/// A one-line job from `start` by `distance` (mm per axis) at `feed_mm_per_s`, or the machine's
/// feed if 0.
[[nodiscard]] Job jog_job(const std::array<double, 3>& start, const std::array<double, 3>& distance, double feed_mm_per_s);

}  // namespace curvestep::host
