// SPDX-License-Identifier: MIT
// LinuxCNC removes blanks everywhere outside comments and ignores case; comments do not nest.
#include "lexer.hpp"

#include <curvestep/core/error.hpp>

namespace curvestep::host::gcode::detail {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

}  // namespace

std::size_t LexedLine::column(std::size_t index) const {
  if (index < columns.size()) return columns[index];
  return columns.empty() ? 1 : columns.back() + 1;
}

LexedLine lex_line(std::string_view source) {
  LexedLine line;
  std::size_t i = 0;
  while (i < source.size() && is_blank(source[i])) ++i;
  if (i < source.size() && source[i] == '/') {
    line.block_delete = true;
    ++i;
  }
  for (; i < source.size(); ++i) {
    const char c = source[i];
    if (is_blank(c)) continue;
    if (c == ';') {
      line.comments.push_back(Comment{i + 1, std::string(source.substr(i + 1)), false});
      break;
    }
    if (c == '(') {
      const std::size_t close = source.find(')', i + 1);
      const std::size_t nested = source.find('(', i + 1);
      if (close == std::string_view::npos) {
        line.error.emplace(i + 1, "(", "the comment is not closed: ')' missing", Error::GcodeSyntax);
        break;
      }
      if (nested < close) {
        line.error.emplace(nested + 1, "(", "comments cannot be nested: '(' inside a comment", Error::GcodeSyntax);
        break;
      }
      line.comments.push_back(Comment{i + 1, std::string(source.substr(i + 1, close - i - 1)), true});
      i = close;
      continue;
    }
    line.text += lower(c);
    line.columns.push_back(i + 1);
  }
  return line;
}

}  // namespace curvestep::host::gcode::detail
