// SPDX-License-Identifier: MIT
// ScratchFolder: a folder of G-code files written by a test (a program and its subroutine files),
// removed with the object.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace curvestep::testing {

/// A fresh folder under the system's temporary folder, named after the test and the process.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : root_(std::filesystem::temp_directory_path() / ("curvestep_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(root_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  /// Writes `text` byte for byte to `relative` (its folders made), and returns its path.
  std::filesystem::path write(const std::string& relative, const std::string& text) const {
    const std::filesystem::path path = root_ / relative;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path;
  }
  /// Makes the folder `relative` and returns its path.
  std::filesystem::path folder(const std::string& relative) const {
    const std::filesystem::path path = root_ / relative;
    std::filesystem::create_directories(path);
    return path;
  }
  /// `relative` below the scratch folder, as a path string (what messages name).
  [[nodiscard]] std::string path(const std::string& relative) const { return (root_ / relative).string(); }
  /// The scratch folder itself.
  [[nodiscard]] const std::filesystem::path& root() const noexcept { return root_; }

 private:
  std::filesystem::path root_;
};

}  // namespace curvestep::testing
