// SPDX-License-Identifier: MIT
#include <curvestep/host/link/console_keys.hpp>

#include <optional>

namespace curvestep::host::link {
namespace {

constexpr char ctrl_d = 0x04;
constexpr char tab = 0x09;
constexpr char ctrl_x = 0x18;
constexpr char escape = 0x1b;
/// Longer escape sequences are no key (a function key with modifiers is about 7 bytes).
constexpr std::size_t max_sequence_length = 16;

/// A whole escape sequence's key (Esc [ A ..., Esc O A ..., Esc [ 5 ~, Esc [ 6 ~), none if unknown.
std::optional<ConsoleKey> sequence_key(std::string_view sequence) {
  const std::string_view body = sequence.substr(2);  // after Esc and the introducer
  if (body == "A") return ConsoleKey::JogYPlus;
  if (body == "B") return ConsoleKey::JogYMinus;
  if (body == "C") return ConsoleKey::JogXPlus;
  if (body == "D") return ConsoleKey::JogXMinus;
  if (body == "5~" && sequence[1] == '[') return ConsoleKey::JogZPlus;
  if (body == "6~" && sequence[1] == '[') return ConsoleKey::JogZMinus;
  return std::nullopt;
}

std::optional<ConsoleKey> plain_key(char key) {
  switch (key) {
    case 'd': case 'D': return ConsoleKey::JogXPlus;
    case 'a': case 'A': return ConsoleKey::JogXMinus;
    case 'w': case 'W': return ConsoleKey::JogYPlus;
    case 's': case 'S': return ConsoleKey::JogYMinus;
    case 'r': case 'R': return ConsoleKey::JogZPlus;
    case 'f': case 'F': return ConsoleKey::JogZMinus;
    case 't': case 'T': case tab: return ConsoleKey::NextStep;
    case 'h': case 'H': return ConsoleKey::Home;
    case '?': return ConsoleKey::Status;
    case escape: case ctrl_x: return ConsoleKey::Abort;
    case 'q': case 'Q': case ctrl_d: return ConsoleKey::Quit;
    default: return std::nullopt;
  }
}

/// The final byte of a CSI or SS3 sequence: 0x40 .. 0x7E after the introducer.
bool final_byte(char c) { return c >= 0x40 && c <= 0x7e; }

}  // namespace

JogDirection jog_direction(ConsoleKey key) noexcept {
  switch (key) {
    case ConsoleKey::JogXPlus: return {0, +1};
    case ConsoleKey::JogXMinus: return {0, -1};
    case ConsoleKey::JogYPlus: return {1, +1};
    case ConsoleKey::JogYMinus: return {1, -1};
    case ConsoleKey::JogZPlus: return {2, +1};
    case ConsoleKey::JogZMinus: return {2, -1};
    default: return {};
  }
}

std::vector<ConsoleKey> ConsoleKeyDecoder::decode(std::string_view bytes) {
  std::vector<ConsoleKey> keys;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    const char c = bytes[k];
    if (!open_sequence_.empty()) {
      open_sequence_ += c;
      if (open_sequence_.size() > 2 && final_byte(c)) {
        if (const auto key = sequence_key(open_sequence_)) keys.push_back(*key);
        open_sequence_.clear();
      } else if (open_sequence_.size() > max_sequence_length) {
        open_sequence_.clear();  // no terminal sends this: drop it
      }
      continue;
    }
    if (c == escape && k + 1 < bytes.size() && (bytes[k + 1] == '[' || bytes[k + 1] == 'O')) {
      open_sequence_ = std::string(1, c);
      continue;
    }
    if (c == escape && k + 1 == bytes.size()) {
      keys.push_back(ConsoleKey::Abort);  // a lone Esc: the key
      continue;
    }
    if (const auto key = plain_key(c)) keys.push_back(*key);
  }
  return keys;
}

std::string_view ConsoleKeyDecoder::key_help() noexcept {
  return "keys: arrows jog X and Y, Page Up / Page Down jog Z (or d a X+/-, w s Y+/-, r f Z+/-), t or Tab jog step "
         "0.1 / 1 / 10 mm, h home, ? status, Esc or Ctrl-X abort the move, q quit";
}

}  // namespace curvestep::host::link
