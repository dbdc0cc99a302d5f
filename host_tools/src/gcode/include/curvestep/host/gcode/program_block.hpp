// SPDX-License-Identifier: MIT
// The seam between the two host-side halves of the G-code reader (docs/gcode.md):
//
//   program text ─► language layer (lexer, parameters, expressions, O-words)
//                      ─► ProgramBlock, one executed line at a time ─► machine layer (modal groups,
//                         offsets, cycles, compensation, events) ─► Job
//
// The language layer hands out each line as LinuxCNC executes it: comments removed (messages kept),
// every expression and parameter reference evaluated to a number, assignments done, control flow
// (O-words) followed, so a loop's body comes out once per pass. It is pulled one block at a time:
// the machine layer executes a block and writes the parameters that depend on the machine state
// (position #5420-#5428, work offsets #5221-#5390, tool #5400, coordinate system #5220) into the
// ParameterStore before it asks for the next block, so the next block's expressions see them.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace curvestep::host::gcode {

/// One word of a block: a letter (upper case) and its value, already evaluated.
struct ProgramWord {
  char letter = 0;          ///< 'G', 'M', 'X', ... (upper case)
  double value = 0;         ///< the number; G and M codes keep their decimals (5.1, 92.3)
  std::size_t column = 0;   ///< 1-based column of the letter in the source line
};

/// A comment that LinuxCNC acts on: (MSG,...), (DEBUG,...) with parameters substituted, (PRINT,...).
struct ProgramMessage {
  enum class Kind { Message, Debug, Print } kind = Kind::Message;
  std::string text;         ///< the text after the comma, parameters substituted
};

/// One executed line.
struct ProgramBlock {
  std::size_t line = 0;                  ///< 1-based line number in the file
  std::string file;                      ///< the subroutine file the line is in (as messages name it), empty for the program's own lines
  std::size_t program_line = 0;          ///< `line` in the program; in a subroutine file, the program's line whose call led there
  std::string source;                    ///< the line as written (for messages)
  bool block_delete = false;             ///< the line started with '/' (it runs: the block delete switch is off)
  std::vector<ProgramWord> words;        ///< the machine words, in the order written (N, O excluded)
  std::vector<ProgramMessage> messages;  ///< MSG / DEBUG / PRINT comments of the line
  /// The word with this letter, or nullptr. A letter appears at most once (the language layer refuses
  /// repeats other than G and M).
  [[nodiscard]] const ProgramWord* find(char letter) const noexcept {
    for (const auto& w : words) {
      if (w.letter == letter) return &w;
    }
    return nullptr;
  }
};

/// Numbered (#1-#5602) and global named (#<_name>) parameters; local names (#<name>, no '_') live in
/// the ProgramReader's call frames. The machine layer writes the system parameters through set()
/// (programs may set #1-#5399 only); `persistent` values (#5161-#5390) may come from the machine file.
class ParameterStore {
 public:
  static constexpr int max_numbered = 5602;
  /// The value of #number (0 if never set); number must be 1..max_numbered.
  [[nodiscard]] double get(int number) const { return numbered_.at(static_cast<std::size_t>(number)); }
  /// Sets #number.
  void set(int number, double value) { numbered_.at(static_cast<std::size_t>(number)) = value; }
  /// A global named parameter ("_name": lower case, without spaces), or nullopt if it does not exist.
  [[nodiscard]] std::optional<double> named(const std::string& name) const {
    const auto found = named_.find(name);
    if (found == named_.end()) return std::nullopt;
    return found->second;
  }
  /// Sets a global named parameter ("_x" for #<_x>).
  void set_named(const std::string& name, double value) { named_[name] = value; }

 private:
  std::vector<double> numbered_ = std::vector<double>(max_numbered + 1, 0.0);
  std::map<std::string, double> named_;
};

}  // namespace curvestep::host::gcode
