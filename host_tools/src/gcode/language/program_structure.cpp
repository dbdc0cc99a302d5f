// SPDX-License-Identifier: MIT
// One pass over the O-words with a stack of open constructs. LinuxCNC's rule: the label that opens
// a construct closes it (o100 if ... o100 endif); a `while` whose label matches an open `do` ends
// that do loop, otherwise it opens a while loop. Labels of if/while/do/repeat are local to their
// subroutine body; subroutine labels are global and unique.
#include "program_structure.hpp"

#include <optional>
#include <utility>

#include <curvestep/host/load_error.hpp>

namespace curvestep::host::gcode::detail {
namespace {

enum class Construct : std::uint8_t { Sub, If, While, Do, Repeat };

struct Open {
  Construct kind;
  std::string label;
  std::size_t line;
  std::size_t last_branch;
  bool has_else = false;
};

std::string_view opener(Construct kind) {
  switch (kind) {
    case Construct::Sub: return "sub";
    case Construct::If: return "if";
    case Construct::While: return "while";
    case Construct::Do: return "do";
    case Construct::Repeat: return "repeat";
  }
  return "?";
}

std::string_view closer(Construct kind) {
  switch (kind) {
    case Construct::Sub: return "endsub";
    case Construct::If: return "endif";
    case Construct::While: return "endwhile";
    case Construct::Do: return "while";
    case Construct::Repeat: return "endrepeat";
  }
  return "?";
}

bool is_loop(Construct kind) { return kind == Construct::While || kind == Construct::Do || kind == Construct::Repeat; }

class Scanner {
 public:
  Scanner(const std::vector<LineSummary>& lines, bool block_delete, const std::string& file)
      : lines_(lines), block_delete_(block_delete), file_(file) {}

  ProgramStructure scan() {
    structure_.links.resize(lines_.size());
    structure_.end = find_end();
    for (std::size_t i = 0; i < structure_.end; ++i) {
      const LineSummary& line = lines_[i];
      if (block_delete_ && line.block_delete) continue;
      const std::size_t enclosing = innermost_loop();
      structure_.links[i].loop = enclosing;
      if (line.oword) visit(i, *line.oword);
    }
    if (!stack_.empty()) {
      const Open& open = stack_.back();
      fail(open.line, "o" + open.label + " " + std::string(opener(open.kind)) + " is not closed: o" + open.label +
                          " " + std::string(closer(open.kind)) + " missing");
    }
    return std::move(structure_);
  }

 private:
  /// The closing '%' of a program whose first non-blank line is '%'.
  std::size_t find_end() const {
    std::size_t i = 0;
    while (i < lines_.size() && lines_[i].blank) ++i;
    if (i == lines_.size() || !lines_[i].percent) return lines_.size();
    for (std::size_t j = i + 1; j < lines_.size(); ++j) {
      if (lines_[j].percent) return j;
    }
    return lines_.size();
  }

  std::size_t innermost_loop() const {
    for (auto it = stack_.rbegin(); it != stack_.rend(); ++it) {
      if (is_loop(it->kind)) return it->line;
    }
    return no_line;
  }

  [[noreturn]] void fail(std::size_t line, const std::string& message) const {
    const OWord& oword = *lines_[line].oword;
    throw LoadError(SourceLocation{file_, line + 1, oword.column, std::nullopt, {}, oword_text(oword)}, message, Error::GcodeSyntax);
  }

  /// The innermost open construct must be `kind` with this line's label.
  Open& expect_top(std::size_t i, const OWord& oword, Construct kind) {
    if (stack_.empty()) {
      fail(i, oword_text(oword) + " without o" + oword.label + " " + std::string(opener(kind)));
    }
    Open& top = stack_.back();
    if (top.kind != kind || top.label != oword.label) {
      fail(i, oword_text(oword) + " does not match the open o" + top.label + " " + std::string(opener(top.kind)) + " (line " +
                  std::to_string(top.line + 1) + ", closed by o" + top.label + " " + std::string(closer(top.kind)) +
                  "): a construct is closed by the label that opened it");
    }
    return top;
  }

  void close(std::size_t i, const Open& top) {
    structure_.links[top.line].closing = i;
    structure_.links[i].opening = top.line;
    structure_.links[i].loop = is_loop(top.kind) ? top.line : structure_.links[i].loop;
    stack_.pop_back();
  }

  void push(std::size_t i, const OWord& oword, Construct kind) {
    stack_.push_back(Open{kind, oword.label, i, i});
    if (is_loop(kind)) structure_.links[i].loop = i;
  }

  void visit(std::size_t i, const OWord& oword) {
    ControlLink& link = structure_.links[i];
    switch (oword.keyword) {
      case Keyword::Sub: {
        if (!stack_.empty()) {
          fail(i, "a subroutine cannot be defined inside o" + stack_.back().label + " " + std::string(opener(stack_.back().kind)) +
                      " (line " + std::to_string(stack_.back().line + 1) + ")");
        }
        const auto [where, inserted] = structure_.subs.emplace(oword.label, i);
        if (!inserted) fail(i, "subroutine o" + oword.label + " is defined twice (first on line " + std::to_string(where->second + 1) + ")");
        push(i, oword, Construct::Sub);
        break;
      }
      case Keyword::Endsub: close(i, expect_top(i, oword, Construct::Sub)); break;
      case Keyword::Return:
        if (stack_.empty() || stack_.front().kind != Construct::Sub || stack_.front().label != oword.label) {
          fail(i, oword_text(oword) + " outside subroutine o" + oword.label + ": return must be inside the sub it names");
        }
        link.opening = stack_.front().line;
        break;
      case Keyword::Call: break;
      case Keyword::If: push(i, oword, Construct::If); break;
      case Keyword::Elseif:
      case Keyword::Else: {
        Open& top = expect_top(i, oword, Construct::If);
        if (top.has_else) fail(i, oword_text(oword) + " after o" + top.label + " else (line " + std::to_string(top.last_branch + 1) + ")");
        structure_.links[top.last_branch].next_branch = i;
        top.last_branch = i;
        top.has_else = oword.keyword == Keyword::Else;
        link.opening = top.line;
        break;
      }
      case Keyword::Endif: {
        Open& top = expect_top(i, oword, Construct::If);
        structure_.links[top.last_branch].next_branch = i;
        close(i, top);
        break;
      }
      case Keyword::While:
        if (!stack_.empty() && stack_.back().kind == Construct::Do && stack_.back().label == oword.label) {
          link.closes_do = true;
          close(i, stack_.back());
        } else {
          push(i, oword, Construct::While);
        }
        break;
      case Keyword::Endwhile: close(i, expect_top(i, oword, Construct::While)); break;
      case Keyword::Do: push(i, oword, Construct::Do); break;
      case Keyword::Repeat: push(i, oword, Construct::Repeat); break;
      case Keyword::Endrepeat: close(i, expect_top(i, oword, Construct::Repeat)); break;
      case Keyword::Break:
      case Keyword::Continue: {
        for (auto it = stack_.rbegin(); it != stack_.rend() && it->kind != Construct::Sub; ++it) {
          if (is_loop(it->kind) && it->label == oword.label) {
            link.opening = it->line;
            return;
          }
        }
        fail(i, oword_text(oword) + " outside a loop labelled o" + oword.label + " (while, do or repeat)");
      }
    }
  }

  const std::vector<LineSummary>& lines_;
  bool block_delete_;
  const std::string& file_;
  ProgramStructure structure_;
  std::vector<Open> stack_;
};

}  // namespace

std::string oword_text(const OWord& oword) {
  return "o" + (oword.label.empty() ? std::string("[...]") : oword.label) + " " + std::string(keyword_name(oword.keyword));
}

LineSummary summarise(const ParsedLine& line, const OWord* oword) noexcept {
  return LineSummary{line.percent, line.block_delete, is_blank(line), oword};
}

ProgramStructure scan_structure(const std::vector<LineSummary>& lines, bool block_delete, const std::string& file) {
  return Scanner(lines, block_delete, file).scan();
}

}  // namespace curvestep::host::gcode::detail
