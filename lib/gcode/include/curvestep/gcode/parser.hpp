// SPDX-License-Identifier: MIT
// G-code line parser: one line of text -> a fixed-capacity Block of words (no heap, no locale).
//
// Why a hand-written number parser: strtod depends on the C locale (a German locale reads "1,5"
// and stops at "1.5"), may allocate on some C libraries, and rounds silently. Here a number is
// [+|-] digits [. digits]; its digits are read into an integer mantissa m (at most 15 significant
// digits, so m < 10^15 < 2^53 is exact in double) and a count d of decimals (d <= 22, so 10^d is
// exact in double). The value is m / 10^d: one IEEE division of two exact operands, hence the
// correctly rounded double of the written decimal (error at most half an ulp, about 1e-16
// relative). Fraction digits beyond the 15th significant one or the 22nd decimal (programs written
// by scripts print 17 digits, "0.30000000000000004") are rounded off by the first dropped digit:
// the value is then within 5e-16 relative of the decimal, far below the Q16.16 grid (2^-16 mm).
// An integer part of more than 15 digits is refused (GcodeBadNumber); nothing wraps. Blanks may
// stand between the digits, as LinuxCNC removes them ("X1 0.5" is X10.5).
//
// Syntax (LinuxCNC's, the part a path needs): letters are case-insensitive; spaces and tabs may
// stand between words and between a letter and its number; "( ... )" is a comment anywhere, ";"
// starts a comment to the end of the line; "%" first on a line (at most a comment after it) is a
// program delimiter; "/" first on a line is block delete (the switch is off: the line runs); "N"
// (line number) may only be the first word. Letters the interpreter does not know are rejected
// here with GcodeUnsupportedWord, so an unsupported word is never silently ignored. A letter
// other than G and M may appear once per line (GcodeConflictingWords otherwise).
//
// Every failure carries the 1-based column of the character at fault (Failure::index), so the
// host can print file:line:column and name the word found there.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include <curvestep/core/result.hpp>

namespace curvestep::gcode {

/// One word: a letter and its number, where it starts on the line.
struct Word {
  char letter = 0;               ///< upper-case letter
  double value = 0;              ///< the number as written (correctly rounded)
  std::int32_t code_tenths = -1; ///< G/M codes: value × 10 ("5.2" -> 52) if exact, else -1
  std::uint16_t column = 0;      ///< 1-based column of the letter
};

/// Whether `c` is LinuxCNC's polar distance (@) or angle (^) word.
[[nodiscard]] constexpr bool is_polar_letter(char c) noexcept { return c == '@' || c == '^'; }

/// The letters the parser accepts (G M N F X Y Z I J K R P Q L S T H D, and the polar @ ^).
[[nodiscard]] constexpr bool is_supported_letter(char letter) noexcept {
  switch (letter) {
    case 'G': case 'M': case 'N': case 'F':
    case 'X': case 'Y': case 'Z':
    case 'I': case 'J': case 'K': case 'R':
    case 'P': case 'Q': case 'L':
    case 'S': case 'T': case 'H': case 'D':
    case '@': case '^':
      return true;
    default:
      return false;
  }
}

/// The words of one line, at most Capacity of them.
template <std::size_t Capacity = 24>
class Block {
  static_assert(Capacity > 0, "a Block holds at least one word");

 public:
  /// The words in line order (N excluded).
  [[nodiscard]] constexpr std::span<const Word> words() const noexcept { return {words_.data(), size_}; }
  [[nodiscard]] constexpr std::size_t size() const noexcept { return size_; }
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  [[nodiscard]] constexpr bool full() const noexcept { return size_ == Capacity; }
  [[nodiscard]] constexpr bool empty() const noexcept { return size_ == 0; }
  /// Appends a word; false if the block is full.
  [[nodiscard]] constexpr bool try_push(const Word& word) noexcept {
    if (full()) return false;
    words_[size_++] = word;
    return true;
  }
  /// The word with `letter` (not G or M, which may repeat), or nullptr.
  [[nodiscard]] constexpr const Word* find(char letter) const noexcept {
    for (std::size_t i = 0; i < size_; ++i) {
      if (words_[i].letter == letter) return &words_[i];
    }
    return nullptr;
  }
  /// The line started with "/" (block delete).
  [[nodiscard]] constexpr bool block_delete() const noexcept { return block_delete_; }
  constexpr void set_block_delete() noexcept { block_delete_ = true; }
  /// Whether the line carried an N word, and its value.
  [[nodiscard]] constexpr bool has_line_number() const noexcept { return has_line_number_; }
  [[nodiscard]] constexpr double line_number() const noexcept { return line_number_; }
  constexpr void set_line_number(double n) noexcept {
    has_line_number_ = true;
    line_number_ = n;
  }

 private:
  std::array<Word, Capacity> words_{};
  std::size_t size_ = 0;
  double line_number_ = 0;
  bool has_line_number_ = false;
  bool block_delete_ = false;
};

namespace detail {

[[nodiscard]] constexpr bool is_blank(char c) noexcept { return c == ' ' || c == '\t' || c == '\r'; }
[[nodiscard]] constexpr bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }
[[nodiscard]] constexpr char to_upper(char c) noexcept { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }
[[nodiscard]] constexpr bool is_letter(char c) noexcept { return to_upper(c) >= 'A' && to_upper(c) <= 'Z'; }

/// 10^k for k = 0..22, all exact in double.
[[nodiscard]] constexpr double power_of_ten(std::size_t k) noexcept {
  double p = 1;
  for (std::size_t i = 0; i < k; ++i) p *= 10;
  return p;
}

[[nodiscard]] constexpr std::size_t column_of(std::size_t position) noexcept { return position + 1; }

}  // namespace detail

/// Most significant digits a number may have.
inline constexpr std::size_t max_significant_digits = 15;
/// Most decimals a number may have (after dropping trailing zeros beyond the significant digits).
inline constexpr std::size_t max_decimals = 22;

/// Parses a number starting at text[position] (blanks before it, after the sign and between digits
/// are skipped) and advances position past it. GcodeBadNumber (index: 1-based column) if there is
/// no digit or the integer part has more than 15 significant digits.
[[nodiscard]] constexpr Result<double> parse_number(std::string_view text, std::size_t& position) noexcept {
  while (position < text.size() && detail::is_blank(text[position])) ++position;
  const std::size_t start = position;
  bool negative = false;
  if (position < text.size() && (text[position] == '+' || text[position] == '-')) {
    negative = text[position] == '-';
    ++position;
    while (position < text.size() && detail::is_blank(text[position])) ++position;
  }
  std::uint64_t mantissa = 0;
  std::size_t significant = 0;
  std::size_t decimals = 0;
  bool any_digit = false;
  bool point = false;
  bool rounded = false;  // digits dropped: the first one decided the rounding
  while (position < text.size()) {
    const char c = text[position];
    if (detail::is_blank(c)) {
      std::size_t next = position;
      while (next < text.size() && detail::is_blank(text[next])) ++next;
      if (next < text.size() && (detail::is_digit(text[next]) || (text[next] == '.' && !point))) {
        position = next;
        continue;
      }
      break;
    }
    if (c == '.' && !point) {
      point = true;
      ++position;
      continue;
    }
    if (!detail::is_digit(c)) break;
    any_digit = true;
    const auto digit = static_cast<std::uint64_t>(c - '0');
    ++position;
    const bool room = significant < max_significant_digits && (!point || decimals < max_decimals);
    if (room && mantissa == 0 && digit == 0) {  // leading zero
      if (point) ++decimals;
      continue;
    }
    if (room && !rounded) {
      mantissa = mantissa * 10 + digit;
      ++significant;
      if (point) ++decimals;
      continue;
    }
    // Beyond 15 significant digits or 22 decimals: an integer part is too long; a fraction is rounded.
    if (!point) return fail(Error::GcodeBadNumber, detail::column_of(start));
    if (!rounded && digit >= 5) ++mantissa;  // < 10^15 + 1 < 2^53: still exact
    rounded = true;
  }
  if (!any_digit) return fail(Error::GcodeBadNumber, detail::column_of(start));
  const double magnitude = static_cast<double>(mantissa) / detail::power_of_ten(decimals);
  return negative ? -magnitude : magnitude;
}

/// value × 10 as an integer if value is a code such as 5, 5.2 or 91.1 (0 <= value < 1000, at most one
/// decimal), else -1.
[[nodiscard]] constexpr std::int32_t code_tenths(double value) noexcept {
  if (!(value >= 0 && value < 1000)) return -1;
  const double scaled = value * 10;
  const auto rounded = static_cast<std::int32_t>(scaled + 0.5);
  // value is the correctly rounded double of a decimal; so is rounded / 10 if the decimal had one digit.
  if (static_cast<double>(rounded) / 10 != value) return -1;
  return rounded;
}

/// Parses one line (without its line break) into a Block. Failures (index: 1-based column of the
/// word or character at fault): GcodeUnsupportedWord (unknown letter),
/// GcodeBadNumber (at the word's letter), GcodeSyntax (a
/// character that starts no word, an unclosed or nested comment, N not first, more than Capacity
/// words),
/// GcodeConflictingWords (a letter other than G/M twice).
template <std::size_t Capacity = 24>
[[nodiscard]] constexpr Result<Block<Capacity>> parse_line(std::string_view text) noexcept {
  Block<Capacity> block;
  std::size_t position = 0;
  bool first_word = true;
  // A program delimiter: "%" first on the line, followed by nothing but blanks and comments.
  bool delimiter = false;
  while (position < text.size() && detail::is_blank(text[position])) ++position;
  if (position < text.size() && text[position] == '%') {
    delimiter = true;
    ++position;
  }
  while (position < text.size()) {
    const char c = text[position];
    if (detail::is_blank(c)) {
      ++position;
      continue;
    }
    if (c == ';') break;
    if (c == '(') {
      const std::size_t open = position;
      ++position;
      while (position < text.size() && text[position] != ')') {
        if (text[position] == '(') return fail(Error::GcodeSyntax, detail::column_of(position));  // nested, as LinuxCNC refuses
        ++position;
      }
      if (position == text.size()) return fail(Error::GcodeSyntax, detail::column_of(open));
      ++position;
      continue;
    }
    if (c == '/') {
      // Block delete, first on the line: the switch is off (as LinuxCNC starts), the line runs.
      if (!first_word || block.block_delete()) return fail(Error::GcodeSyntax, detail::column_of(position));
      block.set_block_delete();
      ++position;
      continue;
    }
    if (!detail::is_letter(c) && !is_polar_letter(c)) return fail(Error::GcodeSyntax, detail::column_of(position));
    if (delimiter) return fail(Error::GcodeSyntax, detail::column_of(position));
    const char letter = detail::to_upper(c);
    const std::size_t letter_position = position;
    if (!is_supported_letter(letter)) return fail(Error::GcodeUnsupportedWord, detail::column_of(letter_position));
    ++position;
    const auto number = parse_number(text, position);
    if (!number) return fail(Error::GcodeBadNumber, detail::column_of(letter_position));  // name the word
    const double value = number.value();
    Word word;
    word.letter = letter;
    word.value = value;
    word.column = static_cast<std::uint16_t>(detail::column_of(letter_position) > 0xFFFF ? 0xFFFF : detail::column_of(letter_position));
    if (letter == 'N') {
      if (!first_word) return fail(Error::GcodeSyntax, detail::column_of(letter_position));
      block.set_line_number(value);
      first_word = false;
      continue;
    }
    first_word = false;
    if (letter == 'G' || letter == 'M') {
      word.code_tenths = code_tenths(value);
    } else if (block.find(letter) != nullptr) {
      return fail(Error::GcodeConflictingWords, detail::column_of(letter_position));
    }
    if (!block.try_push(word)) return fail(Error::GcodeSyntax, detail::column_of(letter_position));
  }
  return block;
}

}  // namespace curvestep::gcode
