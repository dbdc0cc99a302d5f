// SPDX-License-Identifier: MIT
// LineJobRig: the App on a test board B, connected over its serial link, configured (machine(50))
// and moving along a 40 mm line along +x (50 mm/s: about 800 ticks). The common start of the App
// tests that script their board while a job runs (limit switches, tick timing).
#pragma once

#include <optional>

#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/app_settings.hpp>
#include <curvestep/protocol/messages.hpp>

#include "fake_board.hpp"

namespace curvestep::firmware::testing {

template <class B>
struct LineJobRig {
  /// Starts the job with `settings`; `before_job` (a SeekSwitch, say), if given, is sent after the
  /// configuration and before the line.
  explicit LineJobRig(AppSettings settings = {}, std::optional<protocol::Message> before_job = std::nullopt)
      : app(board, settings), host(board, app) {
    REQUIRE(host.connect());
    REQUIRE(host.send(protocol::Message(machine(50))));
    host.pump(5);
    if (before_job) REQUIRE(host.send(*before_job));
    protocol::QueueSegment s = line(p(0, 0), p(40, 0));
    s.end_of_job = true;
    REQUIRE(host.send(protocol::Message(s)));
    REQUIRE(host.send(protocol::Message(protocol::Start{})));
    host.pump(5);
    REQUIRE(app.moving());
    REQUIRE(host.received.errors.empty());
  }
  /// One control tick, a millisecond on the board's clock, then a link exchange.
  void tick() {
    app.on_tick();
    ++board.clock_ms;
    host.pump();
  }
  /// `count` ticks.
  void ticks(int count) {
    for (int k = 0; k < count; ++k) tick();
  }

  B board;
  App<B> app;
  Host<App<B>> host;
};

}  // namespace curvestep::firmware::testing
