// SPDX-License-Identifier: MIT
// A LinuxCNC line: [/] [N...] then either one O-word or any number of words and #assignments.
#include "line_parser.hpp"

#include <array>
#include <utility>

#include <curvestep/host/printable.hpp>

namespace curvestep::host::gcode::detail {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_letter(char c) { return c >= 'a' && c <= 'z'; }
char upper(char c) { return static_cast<char>(c - 'a' + 'A'); }

struct KeywordSpelling {
  std::string_view text;
  Keyword keyword;
};

// Longer spellings first, so that "elseif" is not read as "else" + "if".
constexpr std::array<KeywordSpelling, 15> keywords{{
    {"endrepeat", Keyword::Endrepeat}, {"endwhile", Keyword::Endwhile}, {"continue", Keyword::Continue},
    {"endsub", Keyword::Endsub},       {"elseif", Keyword::Elseif},     {"return", Keyword::Return},
    {"repeat", Keyword::Repeat},       {"endif", Keyword::Endif},       {"while", Keyword::While},
    {"break", Keyword::Break},         {"call", Keyword::Call},         {"else", Keyword::Else},
    {"sub", Keyword::Sub},             {"if", Keyword::If},             {"do", Keyword::Do},
}};

/// (MSG,...), (DEBUG,...), (PRINT,...): the keyword in any case, blanks allowed around it.
std::optional<MessageText> message_of(const Comment& comment) {
  if (!comment.parenthesised) return std::nullopt;
  const std::string& body = comment.body;
  std::size_t i = 0;
  while (i < body.size() && (body[i] == ' ' || body[i] == '\t')) ++i;
  std::string word;
  while (i < body.size() && ((body[i] >= 'a' && body[i] <= 'z') || (body[i] >= 'A' && body[i] <= 'Z'))) {
    word += static_cast<char>(body[i] | 0x20);
    ++i;
  }
  while (i < body.size() && (body[i] == ' ' || body[i] == '\t')) ++i;
  if (i >= body.size() || body[i] != ',') return std::nullopt;
  MessageText message;
  if (word == "msg") {
    message.kind = ProgramMessage::Kind::Message;
  } else if (word == "debug") {
    message.kind = ProgramMessage::Kind::Debug;
  } else if (word == "print") {
    message.kind = ProgramMessage::Kind::Print;
  } else {
    return std::nullopt;
  }
  message.text = body.substr(i + 1);
  return message;
}

/// Skips "n123" at the start (LinuxCNC line numbers are dropped).
void skip_line_number(Cursor& cursor) {
  if (cursor.peek() != 'n') return;
  const std::size_t start = cursor.position();
  cursor.advance();
  if (!is_digit(cursor.peek())) cursor.fail(start, "N (line number) needs digits", Error::GcodeBadNumber);
  while (is_digit(cursor.peek()) || cursor.peek() == '.') cursor.advance();
}

/// "[" ... "]" required for O-word arguments and conditions.
NodeIndex parse_argument(Cursor& cursor, std::vector<Node>& nodes) {
  if (cursor.peek() != '[') {
    cursor.fail(cursor.position(), "O-word arguments and conditions are written in brackets: [...]", Error::GcodeSyntax);
  }
  return parse_real_value(cursor, nodes);
}

OWord parse_oword(Cursor& cursor, std::vector<Node>& nodes) {
  OWord oword;
  const std::size_t start = cursor.position();
  oword.column = cursor.column(start);
  cursor.advance();
  if (cursor.peek() == '<') {
    cursor.advance();
    oword.label = "<" + parse_parameter_name(cursor) + ">";
  } else if (is_digit(cursor.peek())) {
    std::string digits;
    while (is_digit(cursor.peek())) {
      if (!(digits.empty() && cursor.peek() == '0')) digits += cursor.peek();
      cursor.advance();
    }
    oword.label = digits.empty() ? "0" : digits;
  } else if (cursor.peek() == '[' || cursor.peek() == '#') {
    oword.label_value = parse_real_value(cursor, nodes);
  } else {
    cursor.fail(start, "an O-word needs a label: o100 or o<name>", Error::GcodeSyntax);
  }
  const std::size_t keyword_start = cursor.position();
  bool found = false;
  for (const auto& spelling : keywords) {
    if (cursor.starts_with(spelling.text)) {
      oword.keyword = spelling.keyword;
      cursor.advance(spelling.text.size());
      found = true;
      break;
    }
  }
  if (!found && cursor.at_end() && oword.label_value == no_node && oword.label.front() != '<') {
    oword.keyword = Keyword::Program;  // `O100` alone: a numbered program
    return oword;
  }
  if (!found) {
    while (is_letter(cursor.peek())) cursor.advance();
    cursor.fail(keyword_start == cursor.position() ? start : keyword_start,
                "O-word keyword expected (sub endsub return call if elseif else endif while endwhile do repeat endrepeat break continue), "
                "or a numbered program's O100 alone on its line",
                Error::GcodeSyntax);
  }
  if (oword.label_value != no_node && oword.keyword != Keyword::Call) {
    cursor.fail(start, "only call may compute its label (o[...] call)", Error::GcodeSyntax);
  }
  switch (oword.keyword) {
    case Keyword::Call:
      while (!cursor.at_end()) {
        if (oword.arguments.size() == 30) cursor.fail(cursor.position(), "a call takes at most 30 arguments", Error::GcodeSyntax);
        oword.arguments.push_back(parse_argument(cursor, nodes));
      }
      break;
    case Keyword::If: case Keyword::Elseif: case Keyword::While: case Keyword::Repeat:
      if (cursor.at_end()) {
        cursor.fail(start, std::string(keyword_name(oword.keyword)) + " needs a value in brackets: " +
                               std::string(keyword_name(oword.keyword)) + " [...]",
                    Error::GcodeSyntax);
      }
      oword.arguments.push_back(parse_argument(cursor, nodes));
      break;
    case Keyword::Return: case Keyword::Endsub:
      if (!cursor.at_end()) oword.arguments.push_back(parse_argument(cursor, nodes));
      break;
    default: break;
  }
  if (!cursor.at_end()) {
    const std::size_t extra = cursor.position();
    cursor.advance(1);
    cursor.fail(extra, "an O-word line holds nothing else (no words or assignments after the O-word)", Error::GcodeSyntax);
  }
  return oword;
}

Assignment parse_assignment(Cursor& cursor, std::vector<Node>& nodes) {
  Assignment assignment;
  const std::size_t start = cursor.position();
  assignment.column = cursor.column(start);
  cursor.advance();
  if (cursor.peek() == '<') {
    cursor.advance();
    assignment.name = parse_parameter_name(cursor);
  } else {
    assignment.number = parse_real_value(cursor, nodes);
  }
  assignment.end_column = cursor.end_column(cursor.position());
  if (cursor.peek() != '=') {
    cursor.fail(start, "a parameter outside a word must be set: #1=... (to use its value, write it after a letter: X#1)",
                Error::GcodeSyntax);
  }
  cursor.advance();
  assignment.value = parse_real_value(cursor, nodes);
  return assignment;
}

void parse_words(Cursor& cursor, ParsedLine& line) {
  while (!cursor.at_end()) {
    const char c = cursor.peek();
    const std::size_t start = cursor.position();
    if (c == '#') {
      line.assignments.push_back(parse_assignment(cursor, line.nodes));
      continue;
    }
    const bool polar = c == '@' || c == '^';  // LinuxCNC's polar distance and angle words
    if ((c == '$' || c == '?') && start == 0) {
      while (!cursor.at_end()) cursor.advance();
      cursor.fail(start, "a grbl console command ($$, $H, $X, $J=..., ?), not G-code: a sender sends it to grbl, a program does not "
                  "hold it (remove the line)", Error::GcodeSyntax);
    }
    if (!is_letter(c) && !polar) {
      cursor.advance();
      cursor.fail(start, "unexpected character: a word starts with a letter", Error::GcodeSyntax);
    }
    if (c == 'n') cursor.fail(start, "N (line number) must be the first word of the line", Error::GcodeSyntax);
    if (c == 'o') cursor.fail(start, "an O-word must be the first word of its line", Error::GcodeSyntax);
    cursor.advance();
    WordValue word{polar ? c : upper(c), no_node, cursor.column(start)};
    word.value = parse_real_value(cursor, line.nodes);
    if (word.letter != 'G' && word.letter != 'M') {
      for (const auto& other : line.words) {
        if (other.letter == word.letter) {
          cursor.fail(start, std::string("the letter ") + word.letter + " appears twice on the line", Error::GcodeConflictingWords);
        }
      }
    }
    line.words.push_back(word);
  }
}

/// The line's first significant characters are [n digits] 'o'.
bool starts_with_oword(const std::string& text) {
  std::size_t i = 0;
  if (i < text.size() && text[i] == 'n') {
    ++i;
    while (i < text.size() && (is_digit(text[i]) || text[i] == '.')) ++i;
  }
  return i < text.size() && text[i] == 'o';
}

}  // namespace

std::string_view keyword_name(Keyword keyword) noexcept {
  if (keyword == Keyword::Program) return {};
  for (const auto& spelling : keywords) {
    if (spelling.keyword == keyword) return spelling.text;
  }
  return "?";
}

const WordValue* word_of(const ParsedLine& line, char letter) noexcept {
  for (const auto& word : line.words) {
    if (word.letter == letter) return &word;
  }
  return nullptr;
}

const WordValue* literal_m_word(const ParsedLine& line, double code) noexcept {
  for (const auto& word : line.words) {
    if (word.letter != 'M') continue;
    const Node& value = line.nodes[word.value];
    if (value.kind == NodeKind::Number && value.number == code) return &word;
  }
  return nullptr;
}

bool is_blank(const ParsedLine& line) noexcept {
  return !line.percent && !line.oword && !line.error && line.words.empty() && line.assignments.empty() && line.messages.empty();
}

ParsedLine parse_program_line(std::string_view source) {
  const LexedLine lexed = lex_line(source);
  ParsedLine line;
  line.block_delete = lexed.block_delete;
  for (const auto& comment : lexed.comments) {
    if (auto message = message_of(comment)) line.messages.push_back(std::move(*message));
  }
  if (lexed.text == "%") {
    line.percent = true;
    return line;
  }
  const bool oword_line = starts_with_oword(lexed.text);
  Cursor cursor(lexed, source);
  try {
    if (lexed.error) throw *lexed.error;
    skip_line_number(cursor);
    if (oword_line) {
      line.oword = parse_oword(cursor, line.nodes);
    } else {
      parse_words(cursor, line);
    }
  } catch (const LineError& error) {
    if (oword_line) throw;
    line.error = error;
  }
  return line;
}

}  // namespace curvestep::host::gcode::detail
