// SPDX-License-Identifier: MIT
// ProgramReader: the G-code language layer (docs/gcode.md, "The language: parameters, expressions,
// O-words"). It reads a LinuxCNC program and hands out each executed line as a ProgramBlock, with
// comments removed, parameters and expressions evaluated, assignments done and O-word control flow
// followed. It is pulled one block at a time so that the machine layer can write the parameters
// that depend on the machine state (#5420-#5428, ...) between blocks.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <curvestep/host/gcode/program_block.hpp>

namespace curvestep::host::gcode {

/// Lines a program may execute (O-word lines included) before it is taken for an endless loop.
inline constexpr std::size_t default_max_executed_lines = 10'000'000;
/// Lines a program file may have: the reader keeps nothing per line but the O-word lines, and the
/// importer about 140 bytes (docs/robustness.md), so a file cannot make the host run out of memory.
inline constexpr std::size_t default_max_program_lines = 10'000'000;
/// Subroutine calls that may be nested.
inline constexpr std::size_t default_max_call_depth = 64;
/// The highest parameter a program may set; #5400-#5602 are set by the machine layer only.
inline constexpr int max_program_parameter = 5399;

/// How a program is read.
struct ProgramOptions {
  bool block_delete = false;  ///< the block delete switch: on skips lines starting with '/' (LinuxCNC starts with it off)
  std::size_t max_executed_lines = default_max_executed_lines;  ///< IterationLimit beyond this
  std::size_t max_call_depth = default_max_call_depth;          ///< CapacityExceeded beyond this
  std::size_t max_lines = default_max_program_lines;            ///< CapacityExceeded at the line after the last one allowed
  /// Folders searched in this order for the file of a sub the program does not define, as
  /// LinuxCNC's SUBROUTINE_PATH: `o<name> call` reads name.ngc, `o100 call` 100.ngc, the first
  /// found (open_file searches the program's own folder first). An empty path is the working folder.
  std::vector<std::filesystem::path> subroutine_path;
};

/// Reads one program. Every error is a LoadError naming file:line:column and the expression,
/// parameter or O-word at fault, with a G-code error code (GcodeSyntax, GcodeBadNumber, ...),
/// DivisionByZero, IterationLimit (endless loop) or CapacityExceeded (calls nested too deep, a file
/// of more than max_lines lines). A call to a sub the program does not define reads the sub's file
/// (ProgramOptions::subroutine_path) once, checked as the program is, and runs its sub as if it
/// were in the program; its lines' errors and blocks name that file.
class ProgramReader {
 public:
  /// Reads `text` and checks its O-word structure (throws LoadError). `file_name` is used in
  /// messages. The reader reads `text` as it runs, which must outlive it.
  ProgramReader(std::string_view text, std::string file_name, ProgramOptions options = {});
  /// The same for the file at `path`, read as a stream: once for the structure (counting its lines
  /// and keeping its O-word lines), then line by line as the program runs, with a seek for each jump
  /// of its control flow. Without O-words the reader holds nothing per line. Subroutine files are
  /// looked for in the folder of `path` first, then in options.subroutine_path. Throws
  /// std::runtime_error if the file cannot be opened or read.
  [[nodiscard]] static ProgramReader open_file(const std::filesystem::path& path, std::string file_name, ProgramOptions options = {});
  ~ProgramReader();
  ProgramReader(ProgramReader&&) noexcept;
  ProgramReader& operator=(ProgramReader&&) noexcept;
  ProgramReader(const ProgramReader&) = delete;
  ProgramReader& operator=(const ProgramReader&) = delete;

  /// The next executed line that has words or messages, or nullopt at the end of the program
  /// (end of text, closing %, or after the block holding M2 or M30). Throws LoadError.
  [[nodiscard]] std::optional<ProgramBlock> next();
  /// The parameters: numbered ones and the global named ones (#<_name>). Locals live in the reader.
  [[nodiscard]] ParameterStore& parameters() noexcept;
  [[nodiscard]] const ParameterStore& parameters() const noexcept;
  /// True once next() has returned nullopt or handed out an M2/M30 block.
  [[nodiscard]] bool ended() const noexcept;
  /// Subroutine calls active now (0 in the main program).
  [[nodiscard]] std::size_t call_depth() const noexcept;
  /// The lines of the program's file (a last '\n' ends a line, it does not start one).
  [[nodiscard]] std::size_t line_count() const noexcept;

 private:
  class Impl;
  explicit ProgramReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace curvestep::host::gcode
