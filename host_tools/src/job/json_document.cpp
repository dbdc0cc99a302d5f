// SPDX-License-Identifier: MIT
// JSON documents with value lines, and typed reading with located errors.
//
// nlohmann::json keeps no source positions, so after a successful parse a small scanner walks the
// (valid) text once and records the line where every value starts, keyed by its JSON pointer.
// Errors then name the line of the value at fault, or of the object that lacks a key.
#include "json_document.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <curvestep/host/csv.hpp>
#include <curvestep/host/printable.hpp>

namespace curvestep::host::detail {
namespace {

/// What one pass over JSON text finds: the line where every value starts (by JSON pointer), the
/// text of every "type" member, and the pointer of the value being read where the text ends.
struct Scan {
  std::map<std::string, std::size_t> lines;
  std::map<std::string, std::string> types;
  std::string final_pointer;
};

/// Scans `text`, which is valid JSON or a prefix of valid JSON (for locating a syntax error).
Scan scan_json(std::string_view text) {
  struct Frame {
    bool object = false;
    bool expecting_key = false;
    std::size_t index = 0;
    std::string key;
    std::string pointer;  // of the container itself
  };
  Scan scan;
  std::vector<Frame> stack;
  std::size_t line = 1;
  auto current_pointer = [&stack]() -> std::string {
    if (stack.empty()) return "";
    const Frame& top = stack.back();
    return top.pointer + "/" + (top.object ? top.key : std::to_string(top.index));
  };
  auto record = [&](std::size_t at_line) { scan.lines.emplace(current_pointer(), at_line); };
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    if (c == '{' || c == '[') {
      record(line);
      Frame frame;
      frame.object = c == '{';
      frame.expecting_key = frame.object;
      frame.pointer = current_pointer();
      stack.push_back(std::move(frame));
      ++i;
      continue;
    }
    if (c == '}' || c == ']') {
      if (!stack.empty()) stack.pop_back();
      ++i;
      continue;
    }
    if (c == ',') {
      if (!stack.empty()) {
        if (stack.back().object) {
          stack.back().expecting_key = true;
        } else {
          ++stack.back().index;
        }
      }
      ++i;
      continue;
    }
    if (c == ':') {
      if (!stack.empty()) stack.back().expecting_key = false;
      ++i;
      continue;
    }
    if (c == '"') {
      std::string content;
      std::size_t j = i + 1;
      while (j < text.size() && text[j] != '"') {
        if (text[j] == '\\' && j + 1 < text.size()) {
          content += text[j + 1];  // keys and type names need no real unescaping
          j += 2;
          continue;
        }
        content += text[j];
        ++j;
      }
      if (!stack.empty() && stack.back().object && stack.back().expecting_key) {
        stack.back().key = std::move(content);
      } else {
        record(line);
        if (!stack.empty() && stack.back().object && stack.back().key == "type") {
          scan.types[current_pointer()] = std::move(content);
        }
      }
      i = j + 1;
      continue;
    }
    // A number or a literal (true, false, null).
    record(line);
    while (i < text.size() && text[i] != ',' && text[i] != '}' && text[i] != ']' && text[i] != ' ' &&
           text[i] != '\n' && text[i] != '\t' && text[i] != '\r') {
      ++i;
    }
  }
  scan.final_pointer = current_pointer();
  return scan;
}

/// Splits "/segments/3/points/2/1" into the segment (3) and its field ("points"[2][1]); a pointer
/// outside the segments gives the whole path as the field.
void describe_pointer(const std::string& pointer, const Scan& scan, SourceLocation& location) {
  std::vector<std::string> parts;
  std::size_t start = 1;
  while (start <= pointer.size() && !pointer.empty()) {
    const std::size_t slash = pointer.find('/', start);
    parts.push_back(pointer.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  std::size_t first_field = 0;
  if (parts.size() >= 2 && parts[0] == "segments" && !parts[1].empty() &&
      parts[1].find_first_not_of("0123456789") == std::string::npos) {
    location.segment = static_cast<std::size_t>(std::stoul(parts[1]));
    if (const auto type = scan.types.find("/segments/" + parts[1] + "/type"); type != scan.types.end()) {
      location.segment_type = type->second;
    }
    first_field = 2;
  }
  for (std::size_t k = first_field; k < parts.size(); ++k) {
    const bool index = !parts[k].empty() && parts[k].find_first_not_of("0123456789") == std::string::npos;
    if (index && k > first_field) {
      location.field += "[" + parts[k] + "]";
    } else {
      location.field += (location.field.empty() ? "" : ".") + ("\"" + parts[k] + "\"");
    }
  }
}

std::string type_name(const nlohmann::json* pointer) {
  if (pointer == nullptr) return "nothing";
  const nlohmann::json& value = *pointer;
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  if (value.is_boolean()) return "a boolean";
  return "null";
}

/// Offset of the bracket that opens level max_json_depth + 1 of arrays and objects, or npos. Runs
/// before the parser and the line scanner, whose memory would otherwise grow with the depth.
std::size_t too_deep_at(std::string_view text) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_json_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::string_view::npos;
}

/// nlohmann's "... last read: '<token>'" with the token cut to a quotable length.
std::string shorten_last_read(std::string message) {
  const std::string marker = "last read: '";
  const auto open = message.find(marker);
  if (open == std::string::npos) return message;
  const auto start = open + marker.size();
  const auto close = message.rfind('\'');
  if (close == std::string::npos || close < start) return message;
  return message.substr(0, start) + quoted_excerpt(std::string_view(message).substr(start, close - start)) + message.substr(close);
}

}  // namespace

LineColumn line_column(std::string_view text, std::size_t offset) {
  LineColumn position;
  const std::size_t end = std::min(offset, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++position.line;
      position.column = 1;
    } else {
      ++position.column;
    }
  }
  return position;
}

JsonDocument::JsonDocument(std::string_view text, std::string name, Error code) : name_(std::move(name)) {
  // `offset`: the offending byte; the value being read is found by scanning `prefix` bytes.
  auto fail_at = [&](std::size_t offset, std::size_t prefix_length, const std::string& message) {
    const LineColumn position = line_column(text, offset);
    SourceLocation location;
    location.file = name_;
    location.line = position.line;
    location.column = position.column;
    const Scan prefix = scan_json(text.substr(0, std::min(prefix_length, text.size())));
    describe_pointer(prefix.final_pointer, prefix, location);
    throw LoadError(std::move(location), message, code);
  };
  // nlohmann's lexer takes a NUL for the end of the input and would ignore the rest of the file.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
    fail_at(nul, nul, "a NUL byte is not allowed in a JSON file (a binary or truncated file?)");
  }
  if (const auto deep = too_deep_at(text); deep != std::string_view::npos) {
    fail_at(deep, 0, "arrays and objects nested deeper than " + std::to_string(max_json_depth) +
                            " levels (the limit for job and machine files)");
  }
  try {
    root_ = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based index of the last byte read, i.e. the offending one.
    std::string message = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax error while parsing
    // value - invalid literal; last read: 'NaN'": keep the part after the position.
    const auto cause = message.find("syntax error");
    if (cause != std::string::npos) {
      message = message.substr(cause);
    } else if (const auto colon = message.rfind(": "); colon != std::string::npos) {
      message = message.substr(colon + 2);
    }
    const std::size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    fail_at(offset, offset, "invalid JSON: " + shorten_last_read(message));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number too large for a double ("1e999"): nlohmann names the literal but not where it is.
    const std::string message = e.what();
    const auto open = message.find('\'');
    const auto close = message.rfind('\'');
    std::size_t offset = 0;
    std::string literal;
    if (open != std::string::npos && close > open) {
      literal = message.substr(open + 1, close - open - 1);
      if (const auto at = text.find(literal); at != std::string_view::npos) offset = at;
    }
    fail_at(offset, offset + 1, "number " + quoted_excerpt(literal) + " is too large (not finite)");
  }
  lines_ = scan_json(text).lines;
}

std::size_t JsonDocument::line_of(std::string pointer) const {
  while (true) {
    if (const auto found = lines_.find(pointer); found != lines_.end()) return found->second;
    if (pointer.empty()) return 0;
    pointer.erase(pointer.rfind('/'));
  }
}

Node Node::member(const std::string& key) const {
  Node child;
  if (json != nullptr && json->is_object()) {
    if (const auto found = json->find(key); found != json->end()) child.json = &*found;
  }
  child.pointer = pointer + "/" + key;
  child.field = (field.empty() ? "" : field + ".") + "\"" + key + "\"";
  return child;
}

Node Node::element(std::size_t index) const {
  Node child;
  if (json != nullptr && json->is_array() && index < json->size()) child.json = &(*json)[index];
  child.pointer = pointer + "/" + std::to_string(index);
  child.field = field + "[" + std::to_string(index) + "]";
  return child;
}

Node Reader::root() const {
  Node node;
  node.json = &document_->root();
  return node;
}

Node Reader::enter_segment(std::size_t index, Node segment) {
  segment_ = index;
  segment_type_.clear();
  segment.field.clear();
  return segment;
}

void Reader::leave_segment() {
  segment_.reset();
  segment_type_.clear();
}

void Reader::fail(const Node& node, const std::string& message) const { fail(node, message, code_); }

void Reader::fail(const Node& node, const std::string& message, Error code) const {
  SourceLocation location;
  location.file = document_->name();
  location.line = document_->line_of(node.pointer);
  location.segment = segment_;
  location.segment_type = segment_type_;
  location.field = node.field;
  throw LoadError(std::move(location), message, code);
}

void Reader::expect_object(const Node& node) const {
  if (node.json == nullptr || !node.json->is_object()) {
    fail(node, "expected an object, got " + type_name(node.json));
  }
}

void Reader::check_keys(const Node& object, std::initializer_list<std::string_view> allowed) const {
  expect_object(object);
  for (const auto& item : object.json->items()) {
    const std::string& key = item.key();
    if (key == "comment") continue;
    if (std::find(allowed.begin(), allowed.end(), std::string_view(key)) == allowed.end()) {
      std::string known;
      for (const auto name : allowed) known += (known.empty() ? "" : ", ") + std::string(name);
      fail(object.member(key), "unknown key (expected one of: " + known + ", comment)");
    }
  }
}

Node Reader::require(const Node& object, const std::string& key) const {
  expect_object(object);
  Node child = object.member(key);
  if (child.json == nullptr) fail(child, "missing required key");
  return child;
}

std::optional<Node> Reader::optional(const Node& object, const std::string& key) const {
  expect_object(object);
  Node child = object.member(key);
  if (child.json == nullptr) return std::nullopt;
  return child;
}

std::vector<Node> Reader::array(const Node& node, std::size_t min_size, std::size_t max_size) const {
  if (node.json == nullptr || !node.json->is_array()) fail(node, "expected an array, got " + type_name(node.json));
  const std::size_t size = node.json->size();
  if (size < min_size || size > max_size) {
    std::string expected = min_size == max_size ? std::to_string(min_size)
                           : max_size == static_cast<std::size_t>(-1)
                               ? "at least " + std::to_string(min_size)
                               : std::to_string(min_size) + " to " + std::to_string(max_size);
    fail(node, "expected " + expected + " entries, got " + std::to_string(size));
  }
  std::vector<Node> elements;
  elements.reserve(size);
  for (std::size_t i = 0; i < size; ++i) elements.push_back(node.element(i));
  return elements;
}

double Reader::number(const Node& node) const {
  if (node.json == nullptr || !node.json->is_number()) fail(node, "expected a number, got " + type_name(node.json));
  const double value = node.json->get<double>();
  if (!std::isfinite(value)) fail(node, "value is not finite", Error::NotFinite);
  return value;
}

double Reader::positive(const Node& node) const {
  const double value = number(node);
  if (!(value > 0)) fail(node, "value " + format_number(value) + " must be positive");
  return value;
}

std::int64_t Reader::integer(const Node& node, std::int64_t min, std::int64_t max) const {
  const double value = number(node);
  if (std::floor(value) != value || value < static_cast<double>(min) || value > static_cast<double>(max)) {
    fail(node, "value " + format_number(value) + " must be an integer from " + std::to_string(min) + " to " +
                   std::to_string(max));
  }
  return static_cast<std::int64_t>(value);
}

std::string Reader::string(const Node& node) const {
  if (node.json == nullptr || !node.json->is_string()) fail(node, "expected a string, got " + type_name(node.json));
  return node.json->get<std::string>();
}

bool Reader::boolean(const Node& node) const {
  if (node.json == nullptr || !node.json->is_boolean()) fail(node, "expected true or false, got " + type_name(node.json));
  return node.json->get<bool>();
}

}  // namespace curvestep::host::detail
