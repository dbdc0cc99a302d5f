// SPDX-License-Identifier: MIT
// printable(): escapes what a terminal or an XML file would misread.
//
// Why one function: messages quote input (SVG ids, G-code words, file names, JSON numbers). An
// ESC sequence in an id would be executed by the terminal, a NUL or invalid UTF-8 makes an SVG
// malformed, and a 100 KB number makes a 100 KB error line. Every printer passes its text through
// here, so the rule lives in one place: bytes of a valid UTF-8 sequence that is not a control
// character are kept, everything else becomes \xNN.
#include <curvestep/host/printable.hpp>

#include <cstdint>

namespace curvestep::host {
namespace {

void append_hex(std::string& out, unsigned char byte) {
  constexpr const char* digits = "0123456789abcdef";
  out += "\\x";
  out += digits[byte >> 4];
  out += digits[byte & 0x0f];
}

/// Length of the valid UTF-8 sequence starting at `text[i]` (a lead byte >= 0x80), 0 if invalid
/// (overlong forms, surrogates and values above U+10FFFF are invalid).
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  std::uint32_t value = 0;
  if (lead >= 0xc2 && lead <= 0xdf) {
    length = 2;
    value = lead & 0x1fu;
  } else if (lead >= 0xe0 && lead <= 0xef) {
    length = 3;
    value = lead & 0x0fu;
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    length = 4;
    value = lead & 0x07u;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0u) != 0x80u) return 0;
    value = (value << 6) | (byte(i + k) & 0x3fu);
  }
  if (length == 3 && (value < 0x800 || (value >= 0xd800 && value <= 0xdfff))) return 0;
  if (length == 4 && (value < 0x10000 || value > 0x10ffff)) return 0;
  if (value >= 0x80 && value <= 0x9f) return 0;  // C1 control characters (U+0080..U+009F)
  return length;
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\t' || (c >= 0x20 && c < 0x7f)) {
      out += static_cast<char>(c);
      ++i;
    } else if (c == '\n') {
      out += "\\n";
      ++i;
    } else if (c < 0x80) {
      append_hex(out, c);
      ++i;
    } else if (const std::size_t length = utf8_length(text, i); length > 0) {
      out.append(text.substr(i, length));
      i += length;
    } else {
      append_hex(out, c);
      ++i;
    }
  }
  return out;
}

std::string quoted_excerpt(std::string_view text) {
  if (text.size() <= max_quoted_chars) return printable(text);
  std::size_t cut = max_quoted_chars;
  // Do not split a UTF-8 sequence: back up to its lead byte.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0u) == 0x80u) --cut;
  return printable(text.substr(0, cut)) + "...";
}

}  // namespace curvestep::host
