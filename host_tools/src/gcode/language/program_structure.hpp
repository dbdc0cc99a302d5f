// SPDX-License-Identifier: MIT
// The O-word structure of a whole program, found before the first line runs: which line closes
// which construct, the branches of each if, and where each subroutine is defined (so a program may
// call a subroutine defined further down, as LinuxCNC allows). It is found from the O-word lines
// alone and kept per O-word line, so a program without O-words keeps nothing per line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "line_parser.hpp"

namespace curvestep::host::gcode::detail {

inline constexpr std::size_t no_line = static_cast<std::size_t>(-1);

/// What the scan learned about one O-word line or M99 line (0-based line indices; no_line when not
/// applicable).
struct ControlLink {
  std::size_t line = no_line;         ///< the O-word line
  std::size_t opening = no_line;      ///< branch, closing, break, continue, return, M99: the construct's first line
                                      ///< (M99 outside a numbered program: no_line)
  std::size_t closing = no_line;      ///< first line of a construct: its last line (endsub endif endwhile while endrepeat,
                                      ///< a numbered program's M99; the main program's number: no_line)
  std::size_t next_branch = no_line;  ///< if, elseif, else: the next elseif, else or endif
  std::size_t loop = no_line;         ///< the innermost loop containing the line (for the endless-loop message)
  std::size_t loop_after = no_line;   ///< the innermost loop containing the lines after it, up to the next O-word line
  Keyword keyword = Keyword::Sub;
  bool closes_do = false;             ///< a `while` that ends a `do` loop
  bool m99 = false;                   ///< an M99 line (keyword means nothing then)
};

/// The structure of a program: what its O-word lines tell, nothing per other line.
struct ProgramStructure {
  std::vector<ControlLink> links;             ///< one per O-word line and M99 line, in line order
  std::map<std::string, std::size_t> subs;    ///< label ("100", "<name>") -> its `sub` line
  std::map<std::string, std::size_t> numbered;  ///< label ("100") -> its numbered program's `O100` line

  /// The links of O-word line `line` (which must be one of the scanned lines).
  [[nodiscard]] const ControlLink& link(std::size_t line) const;
  /// The innermost loop containing `line`, a line that is not left out by block delete: the
  /// O-word line's own, or that of the lines after the O-word line before it. no_line if none.
  [[nodiscard]] std::size_t loop_containing(std::size_t line) const;
};

/// "o100 endwhile", "o<name> sub": an O-word as messages name it.
[[nodiscard]] std::string oword_text(const OWord& oword);

/// The kinds of construct an O-word opens (program_structure.cpp).
enum class OWordConstruct : std::uint8_t;

/// Finds the structure from the O-word lines of a program, given one at a time in line order (the
/// lines that can run: the reader leaves out those after a closing '%' and, with block delete on,
/// those starting with '/'), so that the reader need not keep their parse. Throws LoadError
/// (file:line:column, the O-word) for a construct closed by another label or keyword, one left
/// open (by finish()), break/continue outside its loop, return outside its subroutine, a
/// subroutine defined twice or inside another construct. Numbered programs (Fanuc style, as
/// LinuxCNC): `O100` on the program's first line is its number; elsewhere it opens a numbered
/// program that the next M99 at its level closes (an M99 deeper in it returns from it). An M99 in
/// a sub is refused; one outside any numbered program is kept (the main program's M99, refused if it runs).
class StructureScan {
 public:
  explicit StructureScan(std::string file);
  ~StructureScan();
  StructureScan(const StructureScan&) = delete;
  StructureScan& operator=(const StructureScan&) = delete;

  /// The next O-word line: `line` its 0-based index; `first_line`: nothing but blanks, comments
  /// and '%' comes before it (an `O100` there is the main program's number).
  void add(std::size_t line, const OWord& oword, bool first_line = false);
  /// The next line with an M99 written as a number, its M word at `column`.
  void add_m99(std::size_t line, std::size_t column);
  /// The structure, once every line is added.
  [[nodiscard]] ProgramStructure finish();

 private:
  using Construct = OWordConstruct;
  struct Open;
  [[nodiscard]] std::size_t innermost_loop() const;
  [[nodiscard]] ControlLink& append(std::size_t line);
  void define(const OWord& oword, Construct kind);
  [[noreturn]] void fail(std::size_t line, std::size_t column, const std::string& field, const std::string& message) const;
  [[noreturn]] void fail(const OWord& oword, const std::string& message) const;
  Open& expect_top(const OWord& oword, Construct kind);
  void close(const Open& top);
  void push(const OWord& oword, Construct kind);
  void visit(const OWord& oword);

  std::string file_;
  ProgramStructure structure_;
  std::vector<Open> stack_;
};

}  // namespace curvestep::host::gcode::detail
