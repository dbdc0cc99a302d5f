// SPDX-License-Identifier: MIT
// One pass over the O-words with a stack of open constructs. LinuxCNC's rule: the label that opens
// a construct closes it (o100 if ... o100 endif); a `while` whose label matches an open `do` ends
// that do loop, otherwise it opens a while loop. Labels of if/while/do/repeat are local to their
// subroutine body; subroutine labels are global and unique. A numbered program (`O100` ... M99)
// is a subroutine body too, opened by its bare O-word and closed by M99.
#include "program_structure.hpp"

#include <algorithm>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>

#include <curvestep/host/load_error.hpp>

namespace curvestep::host::gcode::detail {

enum class OWordConstruct : std::uint8_t { Sub, If, While, Do, Repeat, Program };

/// An open construct: what closing it and naming it in a message need.
struct StructureScan::Open {
  Construct kind;
  std::string label;
  std::size_t line;         ///< the opening line
  std::size_t column;       ///< of its 'o'
  std::size_t slot;         ///< its links' place in structure_.links
  std::size_t last_branch;  ///< if: the slot of its last branch so far
  bool has_else = false;
};

namespace {

using Construct = OWordConstruct;

std::string_view opener(Construct kind) {
  switch (kind) {
    case Construct::Sub: return "sub";
    case Construct::If: return "if";
    case Construct::While: return "while";
    case Construct::Do: return "do";
    case Construct::Repeat: return "repeat";
    case Construct::Program: return "";
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
    case Construct::Program: return "M99";
  }
  return "?";
}

bool is_loop(Construct kind) { return kind == Construct::While || kind == Construct::Do || kind == Construct::Repeat; }
bool is_body(Construct kind) { return kind == Construct::Sub || kind == Construct::Program; }

/// "o100 sub", "o100" (a numbered program): a construct's opening line as messages name it.
std::string opening_text(const std::string& label, Construct kind) {
  return "o" + label + (kind == Construct::Program ? "" : " " + std::string(opener(kind)));
}

/// "o100 endsub", "M99": the line that closes a construct.
std::string closing_text(const std::string& label, Construct kind) {
  return kind == Construct::Program ? std::string("M99") : "o" + label + " " + std::string(closer(kind));
}

/// The first link of a line after `line`.
std::vector<ControlLink>::const_iterator after(const std::vector<ControlLink>& links, std::size_t line) {
  return std::upper_bound(links.begin(), links.end(), line, [](std::size_t l, const ControlLink& link) { return l < link.line; });
}

}  // namespace

StructureScan::StructureScan(std::string file) : file_(std::move(file)) {}
StructureScan::~StructureScan() = default;

ControlLink& StructureScan::append(std::size_t line) {
  ControlLink link;
  link.line = line;
  link.loop = innermost_loop();
  structure_.links.push_back(link);
  return structure_.links.back();
}

void StructureScan::add(std::size_t line, const OWord& oword, bool first_line) {
  append(line).keyword = oword.keyword;
  if (oword.keyword != Keyword::Program || !first_line) visit(oword);  // the main program's number opens nothing
  structure_.links.back().loop_after = innermost_loop();
}

void StructureScan::add_m99(std::size_t line, std::size_t column) {
  ControlLink& link = append(line);
  link.m99 = true;
  if (!stack_.empty() && stack_.back().kind == Construct::Program) {
    close(stack_.back());
  } else if (!stack_.empty() && stack_.front().kind == Construct::Program) {
    link.opening = stack_.front().line;  // inside a construct of the numbered program: returns from it
  } else if (!stack_.empty() && stack_.front().kind == Construct::Sub) {
    const Open& sub = stack_.front();
    fail(line, column, "M99",
         "M99 inside o" + sub.label + " sub (line " + std::to_string(sub.line + 1) + "): a sub ends with o" + sub.label +
             " endsub or returns with o" + sub.label + " return; M99 ends a numbered program (O100 ... M99)");
  }
  structure_.links.back().loop_after = innermost_loop();
}

ProgramStructure StructureScan::finish() {
  if (!stack_.empty()) {
    const Open& open = stack_.back();
    const std::string opening = opening_text(open.label, open.kind);
    fail(open.line, open.column, opening, opening + " is not closed: " + closing_text(open.label, open.kind) + " missing");
  }
  return std::move(structure_);
}

std::size_t StructureScan::innermost_loop() const {
  for (auto it = stack_.rbegin(); it != stack_.rend(); ++it) {
    if (is_loop(it->kind)) return it->line;
  }
  return no_line;
}

void StructureScan::fail(std::size_t line, std::size_t column, const std::string& field, const std::string& message) const {
  throw LoadError(SourceLocation{file_, line + 1, column, std::nullopt, {}, field}, message, Error::GcodeSyntax);
}

/// A failure at the line being added.
void StructureScan::fail(const OWord& oword, const std::string& message) const {
  fail(structure_.links.back().line, oword.column, oword_text(oword), message);
}

/// The innermost open construct must be `kind` with this line's label.
StructureScan::Open& StructureScan::expect_top(const OWord& oword, Construct kind) {
  if (stack_.empty()) fail(oword, oword_text(oword) + " without o" + oword.label + " " + std::string(opener(kind)));
  Open& top = stack_.back();
  if (top.kind != kind || top.label != oword.label) {
    fail(oword, oword_text(oword) + " does not match the open " + opening_text(top.label, top.kind) + " (line " +
                    std::to_string(top.line + 1) + ", closed by " + closing_text(top.label, top.kind) +
                    "): a construct is closed by the label that opened it");
  }
  return top;
}

void StructureScan::close(const Open& top) {
  ControlLink& link = structure_.links.back();
  structure_.links[top.slot].closing = link.line;
  link.opening = top.line;
  if (is_loop(top.kind)) link.loop = top.line;
  stack_.pop_back();
}

void StructureScan::push(const OWord& oword, Construct kind) {
  ControlLink& link = structure_.links.back();
  const std::size_t slot = structure_.links.size() - 1;
  stack_.push_back(Open{kind, oword.label, link.line, oword.column, slot, slot});
  if (is_loop(kind)) link.loop = link.line;
}

void StructureScan::visit(const OWord& oword) {
  ControlLink& link = structure_.links.back();
  const std::size_t line = link.line;
  switch (oword.keyword) {
    case Keyword::Sub: define(oword, Construct::Sub); break;
    case Keyword::Program: define(oword, Construct::Program); break;
    case Keyword::Endsub: close(expect_top(oword, Construct::Sub)); break;
    case Keyword::Return:
      if (stack_.empty() || stack_.front().kind != Construct::Sub || stack_.front().label != oword.label) {
        fail(oword, oword_text(oword) + " outside subroutine o" + oword.label + ": return must be inside the sub it names");
      }
      link.opening = stack_.front().line;
      break;
    case Keyword::Call: break;
    case Keyword::If: push(oword, Construct::If); break;
    case Keyword::Elseif:
    case Keyword::Else: {
      Open& top = expect_top(oword, Construct::If);
      if (top.has_else) {
        fail(oword, oword_text(oword) + " after o" + top.label + " else (line " + std::to_string(structure_.links[top.last_branch].line + 1) + ")");
      }
      structure_.links[top.last_branch].next_branch = line;
      top.last_branch = structure_.links.size() - 1;
      top.has_else = oword.keyword == Keyword::Else;
      link.opening = top.line;
      break;
    }
    case Keyword::Endif: {
      Open& top = expect_top(oword, Construct::If);
      structure_.links[top.last_branch].next_branch = line;
      close(top);
      break;
    }
    case Keyword::While:
      if (!stack_.empty() && stack_.back().kind == Construct::Do && stack_.back().label == oword.label) {
        link.closes_do = true;
        close(stack_.back());
      } else {
        push(oword, Construct::While);
      }
      break;
    case Keyword::Endwhile: close(expect_top(oword, Construct::While)); break;
    case Keyword::Do: push(oword, Construct::Do); break;
    case Keyword::Repeat: push(oword, Construct::Repeat); break;
    case Keyword::Endrepeat: close(expect_top(oword, Construct::Repeat)); break;
    case Keyword::Break:
    case Keyword::Continue: {
      for (auto it = stack_.rbegin(); it != stack_.rend() && !is_body(it->kind); ++it) {
        if (is_loop(it->kind) && it->label == oword.label) {
          link.opening = it->line;
          return;
        }
      }
      fail(oword, oword_text(oword) + " outside a loop labelled o" + oword.label + " (while, do or repeat)");
    }
  }
}

/// A subroutine or numbered program: at the top level, its label used once by either kind.
void StructureScan::define(const OWord& oword, Construct kind) {
  if (!stack_.empty()) {
    fail(oword, std::string(kind == Construct::Sub ? "a subroutine" : "a numbered program") + " cannot be defined inside " +
                    opening_text(stack_.back().label, stack_.back().kind) + " (line " + std::to_string(stack_.back().line + 1) + ")" +
                    (stack_.back().kind == Construct::Program ? ": M99 missing before it?" : ""));
  }
  const std::size_t line = structure_.links.back().line;
  auto& defined = kind == Construct::Sub ? structure_.subs : structure_.numbered;
  const auto& other = kind == Construct::Sub ? structure_.numbered : structure_.subs;
  if (const auto found = other.find(oword.label); found != other.end()) {
    fail(oword, "o" + oword.label + " is defined twice, as a sub and as a numbered program (first on line " +
                    std::to_string(found->second + 1) + ")");
  }
  const auto [where, inserted] = defined.emplace(oword.label, line);
  if (!inserted) {
    fail(oword, std::string(kind == Construct::Sub ? "subroutine" : "numbered program") + " o" + oword.label +
                    " is defined twice (first on line " + std::to_string(where->second + 1) + ")");
  }
  push(oword, kind);
}

std::string oword_text(const OWord& oword) {
  const std::string label = "o" + (oword.label.empty() ? std::string("[...]") : oword.label);
  return oword.keyword == Keyword::Program ? label : label + " " + std::string(keyword_name(oword.keyword));
}

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

}  // namespace curvestep::host::gcode::detail
