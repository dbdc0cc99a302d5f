// SPDX-License-Identifier: MIT
// Internal: a parsed JSON file with the line of every value, and typed accessors whose errors name
// the file, line, segment and field (LoadError). Shared by the job and machine loaders.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host::detail {

/// The deepest nesting of arrays and objects a job or machine file may have (a job needs 4).
inline constexpr std::size_t max_json_depth = 64;

/// Line and column (1-based) of byte offset `offset` in `text`.
struct LineColumn {
  std::size_t line = 1;
  std::size_t column = 1;
};
[[nodiscard]] LineColumn line_column(std::string_view text, std::size_t offset);

/// The JSON text of a file, parsed, with the line where each value starts.
class JsonDocument {
 public:
  /// Parses `text`; a syntax error throws LoadError with line:column and `code`.
  JsonDocument(std::string_view text, std::string name, Error code);

  [[nodiscard]] const nlohmann::json& root() const noexcept { return root_; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  /// Line where the value at `pointer` ("/segments/3/points") starts; falls back to the nearest
  /// enclosing value; 0 if unknown.
  [[nodiscard]] std::size_t line_of(std::string pointer) const;

 private:
  std::string name_;
  nlohmann::json root_;
  std::map<std::string, std::size_t> lines_;
};

/// A value in the document, with its pointer (for the line) and its display name (for messages).
struct Node {
  const nlohmann::json* json = nullptr;  ///< null for a missing member
  std::string pointer;                   ///< "/segments/3/points/2"
  std::string field;                     ///< "\"points\"[2]" (relative to the segment, if any)

  [[nodiscard]] Node member(const std::string& key) const;
  [[nodiscard]] Node element(std::size_t index) const;
};

/// Typed reading with errors that name the file, line, segment and field.
class Reader {
 public:
  Reader(const JsonDocument& document, Error code) : document_(&document), code_(code) {}

  /// The root value.
  [[nodiscard]] Node root() const;
  /// Names segment `index` in later errors; returns `segment` with fields made relative to it.
  [[nodiscard]] Node enter_segment(std::size_t index, Node segment);
  void set_segment_type(std::string type) { segment_type_ = std::move(type); }
  void leave_segment();

  [[noreturn]] void fail(const Node& node, const std::string& message) const;
  [[noreturn]] void fail(const Node& node, const std::string& message, Error code) const;

  /// Rejects keys of `object` that are not in `allowed` ("comment" is always allowed).
  void check_keys(const Node& object, std::initializer_list<std::string_view> allowed) const;
  [[nodiscard]] Node require(const Node& object, const std::string& key) const;
  [[nodiscard]] std::optional<Node> optional(const Node& object, const std::string& key) const;
  void expect_object(const Node& node) const;
  [[nodiscard]] std::vector<Node> array(const Node& node, std::size_t min_size, std::size_t max_size) const;
  /// A finite number.
  [[nodiscard]] double number(const Node& node) const;
  /// A finite number > 0.
  [[nodiscard]] double positive(const Node& node) const;
  /// An integer in [min, max].
  [[nodiscard]] std::int64_t integer(const Node& node, std::int64_t min, std::int64_t max) const;
  [[nodiscard]] std::string string(const Node& node) const;
  /// true or false.
  [[nodiscard]] bool boolean(const Node& node) const;

 private:
  const JsonDocument* document_;
  Error code_;
  std::optional<std::size_t> segment_;
  std::string segment_type_;
};

}  // namespace curvestep::host::detail
