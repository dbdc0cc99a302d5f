// SPDX-License-Identifier: MIT
// Test vectors of the seed digests (/work/shared/docs/seeds/) used by more than one test suite.
#pragma once

#include <array>

namespace curvestep::testing {

/// Digest 001 Example 1.2, the cubic (0,1),(0,4),(5,5),(7,0), at t = k/8 for k = 0..8 (TV-03, TV-05):
/// exact binary fractions.
inline constexpr std::array<std::array<double, 2>, 9> example_1_2_eighths{{{0, 1},
                                                                           {7 / 32., 259 / 128.},
                                                                           {13 / 16., 45 / 16.},
                                                                           {27 / 16., 425 / 128.},
                                                                           {11 / 4., 7 / 2.},
                                                                           {125 / 32., 423 / 128.},
                                                                           {81 / 16., 43 / 16.},
                                                                           {49 / 8., 205 / 128.},
                                                                           {7, 0}}};

}  // namespace curvestep::testing
