// SPDX-License-Identifier: MIT
// ConsoleKeyDecoder: the idle console's keys from the bytes a terminal sends (xterm's cursor and
// editing-pad sequences, ECMA-48: Esc [ A..D, Esc O A..D in application mode, Esc [ 5 ~ / 6 ~), the
// letters for terminals without them, a sequence cut between two reads, a lone Esc.
#include <catch2/catch.hpp>

#include <vector>

#include <curvestep/host/link/console_keys.hpp>

using curvestep::host::link::ConsoleKey;
using curvestep::host::link::ConsoleKeyDecoder;
using curvestep::host::link::jog_direction;

TEST_CASE("console keys: arrows, Page Up and Page Down jog the axes, letters too", "[host_tools][link][console]") {
  ConsoleKeyDecoder decoder;
  using K = ConsoleKey;
  CHECK(decoder.decode("\x1b[A\x1b[B\x1b[C\x1b[D\x1b[5~\x1b[6~") ==
        std::vector<K>{K::JogYPlus, K::JogYMinus, K::JogXPlus, K::JogXMinus, K::JogZPlus, K::JogZMinus});
  CHECK(decoder.decode("\x1bOA\x1bOD") == std::vector<K>{K::JogYPlus, K::JogXMinus});  // application cursor mode
  CHECK(decoder.decode("dawsrf") == std::vector<K>{K::JogXPlus, K::JogXMinus, K::JogYPlus, K::JogYMinus, K::JogZPlus, K::JogZMinus});
  CHECK(decoder.decode("t\th?q\x04") == std::vector<K>{K::NextStep, K::NextStep, K::Home, K::Status, K::Quit, K::Quit});
  CHECK(jog_direction(K::JogXPlus).axis == 0);
  CHECK(jog_direction(K::JogXPlus).sign == 1);
  CHECK(jog_direction(K::JogYMinus).axis == 1);
  CHECK(jog_direction(K::JogYMinus).sign == -1);
  CHECK(jog_direction(K::JogZPlus).axis == 2);
  CHECK(jog_direction(K::Home).axis == 3);
}

TEST_CASE("console keys: a sequence cut between reads, unknown sequences, a lone Esc and Ctrl-X", "[host_tools][link][console]") {
  ConsoleKeyDecoder decoder;
  using K = ConsoleKey;
  CHECK(decoder.decode("d\x1b[").empty() == false);  // d now, the arrow open
  CHECK(decoder.decode("C") == std::vector<K>{K::JogXPlus});
  CHECK(decoder.decode("\x1b[5").empty());
  CHECK(decoder.decode("~") == std::vector<K>{K::JogZPlus});
  // F5 (Esc [ 1 5 ~) and Home (Esc [ H) are no console keys: skipped whole, the next key counts.
  CHECK(decoder.decode("\x1b[15~\x1b[Hq") == std::vector<K>{K::Quit});
  CHECK(decoder.decode("\x1b") == std::vector<K>{K::Abort});
  CHECK(decoder.decode("\x18") == std::vector<K>{K::Abort});
  CHECK(decoder.decode("\x1bq") == std::vector<K>{K::Abort, K::Quit});  // Esc then q, typed fast
  CHECK(decoder.decode("x!~z").empty());  // no console keys
}
