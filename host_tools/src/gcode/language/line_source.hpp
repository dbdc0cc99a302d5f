// SPDX-License-Identifier: MIT
// LineSource: a program's lines, read one at a time from a seekable byte stream (text in memory, or
// a file through a 64 KiB window), so that the reader holds one line of the program, not the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>

namespace curvestep::host::gcode::detail {

/// The lines of a program as written. Every '\n' ends a line and the text after the last one is a
/// line too (empty or not): n newlines make n + 1 lines, so an empty program is one empty line.
class LineSource {
 public:
  virtual ~LineSource() = default;
  /// The next line without its '\n' (a '\r' before it is kept), or nullopt after the last line.
  /// The view is valid until the next call of next() or seek().
  [[nodiscard]] virtual std::optional<std::string_view> next() = 0;
  /// True once the last line has been returned.
  [[nodiscard]] virtual bool at_end() const noexcept = 0;
  /// The byte offset where the next line starts.
  [[nodiscard]] virtual std::uint64_t offset() const noexcept = 0;
  /// Goes on from `offset`, a value offset() returned before.
  virtual void seek(std::uint64_t offset) = 0;
};

/// The lines of `text`, which must outlive the source.
[[nodiscard]] std::unique_ptr<LineSource> text_lines(std::string_view text);

/// The lines of the file at `path`. Throws std::runtime_error "PATH: cannot open the file" (or
/// "cannot read the file" when a read fails), as read_text_file does.
[[nodiscard]] std::unique_ptr<LineSource> file_lines(const std::filesystem::path& path);

}  // namespace curvestep::host::gcode::detail
