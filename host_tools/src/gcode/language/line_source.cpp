// SPDX-License-Identifier: MIT
// The two line sources: a view of text in memory, and a file read through a window of 64 KiB that
// a seek inside it does not refill (a loop whose body fits in the window runs without reading).
#include "line_source.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace curvestep::host::gcode::detail {
namespace {

class TextLines final : public LineSource {
 public:
  explicit TextLines(std::string_view text) : text_(text) {}

  std::optional<std::string_view> next() override {
    if (at_end_) return std::nullopt;
    const std::size_t start = position_;
    const std::size_t stop = text_.find('\n', start);
    if (stop == std::string_view::npos) {
      position_ = text_.size();
      at_end_ = true;
      return text_.substr(start);
    }
    position_ = stop + 1;
    return text_.substr(start, stop - start);
  }

  [[nodiscard]] bool at_end() const noexcept override { return at_end_; }
  [[nodiscard]] std::uint64_t offset() const noexcept override { return position_; }

  void seek(std::uint64_t offset) override {
    position_ = static_cast<std::size_t>(std::min<std::uint64_t>(offset, text_.size()));
    at_end_ = false;
  }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  bool at_end_ = false;
};

class FileLines final : public LineSource {
 public:
  explicit FileLines(const std::filesystem::path& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw std::runtime_error(path_.string() + ": cannot open the file");
  }

  std::optional<std::string_view> next() override {
    if (at_end_) return std::nullopt;
    line_.clear();
    for (;;) {
      if (position_ == filled_ && !fill()) {
        at_end_ = true;
        break;
      }
      const char* begin = window_.data() + position_;
      const char* end = window_.data() + filled_;
      const char* newline = std::find(begin, end, '\n');
      line_.append(begin, newline);
      position_ += static_cast<std::size_t>(newline - begin);
      if (newline != end) {
        ++position_;
        break;
      }
    }
    return std::string_view(line_);
  }

  [[nodiscard]] bool at_end() const noexcept override { return at_end_; }
  [[nodiscard]] std::uint64_t offset() const noexcept override { return window_start_ + position_; }

  void seek(std::uint64_t offset) override {
    at_end_ = false;
    if (offset >= window_start_ && offset <= window_start_ + filled_) {
      position_ = static_cast<std::size_t>(offset - window_start_);
      return;
    }
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    if (!in_) throw std::runtime_error(path_.string() + ": cannot read the file");
    window_start_ = offset;
    filled_ = 0;
    position_ = 0;
  }

 private:
  static constexpr std::size_t window_bytes = 64 * 1024;

  /// The window's next bytes from the file; false at its end.
  bool fill() {
    window_start_ += filled_;
    position_ = 0;
    in_.clear();
    in_.read(window_.data(), static_cast<std::streamsize>(window_.size()));
    if (in_.bad()) throw std::runtime_error(path_.string() + ": cannot read the file");
    filled_ = static_cast<std::size_t>(in_.gcount());
    return filled_ > 0;
  }

  std::filesystem::path path_;
  std::ifstream in_;
  std::vector<char> window_ = std::vector<char>(window_bytes);
  std::uint64_t window_start_ = 0;  ///< file offset of window_[0]
  std::size_t filled_ = 0;          ///< bytes of the window read from the file
  std::size_t position_ = 0;        ///< the next line's start in the window
  std::string line_;
  bool at_end_ = false;
};

}  // namespace

std::unique_ptr<LineSource> text_lines(std::string_view text) { return std::make_unique<TextLines>(text); }

std::unique_ptr<LineSource> file_lines(const std::filesystem::path& path) { return std::make_unique<FileLines>(path); }

}  // namespace curvestep::host::gcode::detail
