// SPDX-License-Identifier: MIT
// adjusted_override: the operator's override commands step the feed by 10 % and 1 %, reset it to
// 100 %, set the rapid override to grbl's three levels, and stop at the ends of the ranges.
#include <catch2/catch.hpp>

#include <curvestep/host/link/operator_command.hpp>

using curvestep::FeedOverride;
using curvestep::host::link::adjusted_override;
using curvestep::host::link::changes_override;
using curvestep::host::link::OperatorCommand;

TEST_CASE("operator override: steps, reset, rapid levels and the ends of the ranges", "[host_tools][link][override]") {
  const FeedOverride start{100, 100};
  CHECK(adjusted_override(start, OperatorCommand::FeedPlus10) == FeedOverride{110, 100});
  CHECK(adjusted_override(start, OperatorCommand::FeedMinus10) == FeedOverride{90, 100});
  CHECK(adjusted_override(start, OperatorCommand::FeedPlus1) == FeedOverride{101, 100});
  CHECK(adjusted_override(start, OperatorCommand::FeedMinus1) == FeedOverride{99, 100});
  CHECK(adjusted_override(FeedOverride{37, 50}, OperatorCommand::FeedReset) == FeedOverride{100, 50});
  CHECK(adjusted_override(start, OperatorCommand::RapidQuarter) == FeedOverride{100, 25});
  CHECK(adjusted_override(start, OperatorCommand::RapidHalf) == FeedOverride{100, 50});
  CHECK(adjusted_override(FeedOverride{100, 25}, OperatorCommand::RapidFull) == FeedOverride{100, 100});
  // A step past an end stops at the end (grbl's rule).
  CHECK(adjusted_override(FeedOverride{195, 100}, OperatorCommand::FeedPlus10) == FeedOverride{200, 100});
  CHECK(adjusted_override(FeedOverride{200, 100}, OperatorCommand::FeedPlus1) == FeedOverride{200, 100});
  CHECK(adjusted_override(FeedOverride{15, 100}, OperatorCommand::FeedMinus10) == FeedOverride{10, 100});
  CHECK(adjusted_override(FeedOverride{10, 100}, OperatorCommand::FeedMinus1) == FeedOverride{10, 100});
  // Only the override commands change it.
  for (const OperatorCommand c : {OperatorCommand::None, OperatorCommand::Hold, OperatorCommand::Resume, OperatorCommand::Abort,
                                  OperatorCommand::Status}) {
    CHECK_FALSE(changes_override(c));
    CHECK(adjusted_override(FeedOverride{120, 50}, c) == FeedOverride{120, 50});
  }
  CHECK(changes_override(OperatorCommand::FeedPlus10));
  CHECK(changes_override(OperatorCommand::RapidQuarter));
}
