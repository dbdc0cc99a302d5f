// SPDX-License-Identifier: MIT
// One pass over the O-words with a stack of open constructs. LinuxCNC's rule: the label that opens
// a construct closes it (o100 if ... o100 endif); a `while` whose label matches an open `do` ends
// that do loop, otherwise it opens a while loop. Labels of if/while/do/repeat are local to their
// subroutine body; subroutine labels are global and unique.
#include "program_structure.hpp"

#include <algorithm>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>

#include <curvestep/host/load_error.hpp>

namespace curvestep::host::gcode::detail {
namespace {

enum class Construct : std::uint8_t { Sub, If, While, Do, Repeat };

struct Open {
  Construct kind;
  std::string label;
  std::size_t line;         ///< the opening line
  std::size_t slot;         ///< its place in the scanned lines
  std::size_t last_branch;  ///< if: the slot of its last branch so far
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
  Scanner(const std::vector<OWordLine>& lines, const std::string& file) : lines_(lines), file_(file) {}

  ProgramStructure scan() {
    structure_.links.resize(lines_.size());
    for (std::size_t slot = 0; slot < lines_.size(); ++slot) {
      ControlLink& link = structure_.links[slot];
      link.line = lines_[slot].line;
      link.loop = innermost_loop();
      visit(slot, *lines_[slot].oword);
      link.loop_after = innermost_loop();
    }
    if (!stack_.empty()) {
      const Open& open = stack_.back();
      fail(open.slot, "o" + open.label + " " + std::string(opener(open.kind)) + " is not closed: o" + open.label + " " +
                          std::string(closer(open.kind)) + " missing");
    }
    return std::move(structure_);
  }

 private:
  std::size_t innermost_loop() const {
    for (auto it = stack_.rbegin(); it != stack_.rend(); ++it) {
      if (is_loop(it->kind)) return it->line;
    }
    return no_line;
  }

  [[noreturn]] void fail(std::size_t slot, const std::string& message) const {
    const OWord& oword = *lines_[slot].oword;
    throw LoadError(SourceLocation{file_, lines_[slot].line + 1, oword.column, std::nullopt, {}, oword_text(oword)}, message,
                    Error::GcodeSyntax);
  }

  /// The innermost open construct must be `kind` with this line's label.
  Open& expect_top(std::size_t slot, const OWord& oword, Construct kind) {
    if (stack_.empty()) {
      fail(slot, oword_text(oword) + " without o" + oword.label + " " + std::string(opener(kind)));
    }
    Open& top = stack_.back();
    if (top.kind != kind || top.label != oword.label) {
      fail(slot, oword_text(oword) + " does not match the open o" + top.label + " " + std::string(opener(top.kind)) + " (line " +
                     std::to_string(top.line + 1) + ", closed by o" + top.label + " " + std::string(closer(top.kind)) +
                     "): a construct is closed by the label that opened it");
    }
    return top;
  }

  void close(std::size_t slot, const Open& top) {
    ControlLink& link = structure_.links[slot];
    structure_.links[top.slot].closing = link.line;
    link.opening = top.line;
    if (is_loop(top.kind)) link.loop = top.line;
    stack_.pop_back();
  }

  void push(std::size_t slot, const OWord& oword, Construct kind) {
    const std::size_t line = lines_[slot].line;
    stack_.push_back(Open{kind, oword.label, line, slot, slot});
    if (is_loop(kind)) structure_.links[slot].loop = line;
  }

  void visit(std::size_t slot, const OWord& oword) {
    ControlLink& link = structure_.links[slot];
    const std::size_t line = link.line;
    switch (oword.keyword) {
      case Keyword::Sub: {
        if (!stack_.empty()) {
          fail(slot, "a subroutine cannot be defined inside o" + stack_.back().label + " " + std::string(opener(stack_.back().kind)) +
                         " (line " + std::to_string(stack_.back().line + 1) + ")");
        }
        const auto [where, inserted] = structure_.subs.emplace(oword.label, line);
        if (!inserted) {
          fail(slot, "subroutine o" + oword.label + " is defined twice (first on line " + std::to_string(where->second + 1) + ")");
        }
        push(slot, oword, Construct::Sub);
        break;
      }
      case Keyword::Endsub: close(slot, expect_top(slot, oword, Construct::Sub)); break;
      case Keyword::Return:
        if (stack_.empty() || stack_.front().kind != Construct::Sub || stack_.front().label != oword.label) {
          fail(slot, oword_text(oword) + " outside subroutine o" + oword.label + ": return must be inside the sub it names");
        }
        link.opening = stack_.front().line;
        break;
      case Keyword::Call: break;
      case Keyword::If: push(slot, oword, Construct::If); break;
      case Keyword::Elseif:
      case Keyword::Else: {
        Open& top = expect_top(slot, oword, Construct::If);
        if (top.has_else) {
          fail(slot, oword_text(oword) + " after o" + top.label + " else (line " +
                         std::to_string(structure_.links[top.last_branch].line + 1) + ")");
        }
        structure_.links[top.last_branch].next_branch = line;
        top.last_branch = slot;
        top.has_else = oword.keyword == Keyword::Else;
        link.opening = top.line;
        break;
      }
      case Keyword::Endif: {
        Open& top = expect_top(slot, oword, Construct::If);
        structure_.links[top.last_branch].next_branch = line;
        close(slot, top);
        break;
      }
      case Keyword::While:
        if (!stack_.empty() && stack_.back().kind == Construct::Do && stack_.back().label == oword.label) {
          link.closes_do = true;
          close(slot, stack_.back());
        } else {
          push(slot, oword, Construct::While);
        }
        break;
      case Keyword::Endwhile: close(slot, expect_top(slot, oword, Construct::While)); break;
      case Keyword::Do: push(slot, oword, Construct::Do); break;
      case Keyword::Repeat: push(slot, oword, Construct::Repeat); break;
      case Keyword::Endrepeat: close(slot, expect_top(slot, oword, Construct::Repeat)); break;
      case Keyword::Break:
      case Keyword::Continue: {
        for (auto it = stack_.rbegin(); it != stack_.rend() && it->kind != Construct::Sub; ++it) {
          if (is_loop(it->kind) && it->label == oword.label) {
            link.opening = it->line;
            return;
          }
        }
        fail(slot, oword_text(oword) + " outside a loop labelled o" + oword.label + " (while, do or repeat)");
      }
    }
  }

  const std::vector<OWordLine>& lines_;
  const std::string& file_;
  ProgramStructure structure_;
  std::vector<Open> stack_;
};

}  // namespace

std::string oword_text(const OWord& oword) {
  return "o" + (oword.label.empty() ? std::string("[...]") : oword.label) + " " + std::string(keyword_name(oword.keyword));
}

namespace {

/// The first link of a line after `line`.
std::vector<ControlLink>::const_iterator after(const std::vector<ControlLink>& links, std::size_t line) {
  return std::upper_bound(links.begin(), links.end(), line, [](std::size_t l, const ControlLink& link) { return l < link.line; });
}

}  // namespace

const ControlLink& ProgramStructure::link(std::size_t line) const {
  const auto found = after(links, line);
  if (found == links.begin() || std::prev(found)->line != line) {
    throw std::logic_error("line " + std::to_string(line + 1) + " is not an O-word line of the structure");
  }
  return *std::prev(found);
}

std::size_t ProgramStructure::loop_containing(std::size_t line) const {
  const auto found = after(links, line);
  if (found == links.begin()) return no_line;
  const ControlLink& before = *std::prev(found);
  return before.line == line ? before.loop : before.loop_after;
}

ProgramStructure scan_structure(const std::vector<OWordLine>& lines, const std::string& file) { return Scanner(lines, file).scan(); }

}  // namespace curvestep::host::gcode::detail
