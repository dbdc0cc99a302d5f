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

enum class OWordConstruct : std::uint8_t { Sub, If, While, Do, Repeat };

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

/// The first link of a line after `line`.
std::vector<ControlLink>::const_iterator after(const std::vector<ControlLink>& links, std::size_t line) {
  return std::upper_bound(links.begin(), links.end(), line, [](std::size_t l, const ControlLink& link) { return l < link.line; });
}

}  // namespace

StructureScan::StructureScan(std::string file) : file_(std::move(file)) {}
StructureScan::~StructureScan() = default;

void StructureScan::add(std::size_t line, const OWord& oword) {
  ControlLink link;
  link.line = line;
  link.keyword = oword.keyword;
  link.loop = innermost_loop();
  structure_.links.push_back(link);
  visit(oword);
  structure_.links.back().loop_after = innermost_loop();
}

ProgramStructure StructureScan::finish() {
  if (!stack_.empty()) {
    const Open& open = stack_.back();
    const std::string opening = "o" + open.label + " " + std::string(opener(open.kind));
    fail(open.line, open.column, opening, opening + " is not closed: o" + open.label + " " + std::string(closer(open.kind)) + " missing");
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
    fail(oword, oword_text(oword) + " does not match the open o" + top.label + " " + std::string(opener(top.kind)) + " (line " +
                    std::to_string(top.line + 1) + ", closed by o" + top.label + " " + std::string(closer(top.kind)) +
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
    case Keyword::Sub: {
      if (!stack_.empty()) {
        fail(oword, "a subroutine cannot be defined inside o" + stack_.back().label + " " + std::string(opener(stack_.back().kind)) +
                        " (line " + std::to_string(stack_.back().line + 1) + ")");
      }
      const auto [where, inserted] = structure_.subs.emplace(oword.label, line);
      if (!inserted) fail(oword, "subroutine o" + oword.label + " is defined twice (first on line " + std::to_string(where->second + 1) + ")");
      push(oword, Construct::Sub);
      break;
    }
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
      for (auto it = stack_.rbegin(); it != stack_.rend() && it->kind != Construct::Sub; ++it) {
        if (is_loop(it->kind) && it->label == oword.label) {
          link.opening = it->line;
          return;
        }
      }
      fail(oword, oword_text(oword) + " outside a loop labelled o" + oword.label + " (while, do or repeat)");
    }
  }
}

std::string oword_text(const OWord& oword) {
  return "o" + (oword.label.empty() ? std::string("[...]") : oword.label) + " " + std::string(keyword_name(oword.keyword));
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
