// SPDX-License-Identifier: MIT
// The O-word structure of a whole program, found before the first line runs: which line closes
// which construct, the branches of each if, and where each subroutine is defined (so a program may
// call a subroutine defined further down, as LinuxCNC allows).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "line_parser.hpp"

namespace curvestep::host::gcode::detail {

inline constexpr std::size_t no_line = static_cast<std::size_t>(-1);

/// What the scan learned about one line (0-based line indices; no_line when not applicable).
struct ControlLink {
  std::size_t opening = no_line;      ///< branch, closing, break, continue, return: the construct's first line
  std::size_t closing = no_line;      ///< first line of a construct: its last line (endsub endif endwhile while endrepeat)
  std::size_t next_branch = no_line;  ///< if, elseif, else: the next elseif, else or endif
  std::size_t loop = no_line;         ///< the innermost loop containing the line (for the endless-loop message)
  bool closes_do = false;             ///< a `while` that ends a `do` loop
};

/// What the scan needs of one line (ParsedLine keeps more: the reader keeps a ParsedLine only for
/// O-word lines, so `oword` points into the reader's own store).
struct LineSummary {
  bool percent = false;       ///< a '%' delimiter line
  bool block_delete = false;  ///< starts with '/'
  bool blank = false;         ///< is_blank(): nothing but blanks and plain comments
  const OWord* oword = nullptr;
};

/// The summary of a parsed line; `oword` is the line's own O-word (nullptr if none).
[[nodiscard]] LineSummary summarise(const ParsedLine& line, const OWord* oword) noexcept;

/// The structure of a program.
struct ProgramStructure {
  std::vector<ControlLink> links;             ///< one per line
  std::map<std::string, std::size_t> subs;    ///< label ("100", "<name>") -> its `sub` line
  std::size_t end = 0;                        ///< lines from here on are not part of the program (closing %)
};

/// "o100 endwhile", "o<name> sub": an O-word as messages name it.
[[nodiscard]] std::string oword_text(const OWord& oword);

/// Scans the lines; throws LoadError (file:line:column, the O-word) for a construct closed by
/// another label or keyword, one left open, break/continue outside its loop, return outside its
/// subroutine, a subroutine defined twice or inside another construct. Lines starting with '/' are
/// left out when `block_delete` is on.
[[nodiscard]] ProgramStructure scan_structure(const std::vector<LineSummary>& lines, bool block_delete, const std::string& file);

}  // namespace curvestep::host::gcode::detail
