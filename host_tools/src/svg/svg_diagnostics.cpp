// SPDX-License-Identifier: MIT
// Errors and warnings of one SVG file (svg_diagnostics.hpp).
#include "svg_diagnostics.hpp"

#include <algorithm>

namespace curvestep::host::svg {

std::string Diagnostics::label(const tinyxml2::XMLElement& element) {
  std::string text = "<" + std::string(element.Name());
  if (const char* id = element.Attribute("id")) text += " id=\"" + std::string(id) + "\"";
  return text + ">";
}

std::string Diagnostics::field(const tinyxml2::XMLElement& element, const char* attribute) {
  std::string text = label(element);
  if (attribute != nullptr && *attribute != '\0') text += " \"" + std::string(attribute) + "\"";
  return text;
}

void Diagnostics::fail_at(std::size_t line, const std::string& field, const std::string& message, Error code) const {
  SourceLocation location;
  location.file = file_;
  location.line = line;
  location.field = field;
  throw LoadError(std::move(location), message, code);
}

void Diagnostics::fail(const tinyxml2::XMLElement& element, const char* attribute, const std::string& message, Error code) const {
  fail_at(static_cast<std::size_t>(element.GetLineNum()), field(element, attribute), message, code);
}

void Diagnostics::fail_syntax(const tinyxml2::XMLElement& element, const char* attribute, const SyntaxError& error) const {
  fail(element, attribute, "at character " + std::to_string(error.position()) + ": " + error.what());
}

std::string Diagnostics::line(const tinyxml2::XMLElement& element, const std::string& message) const {
  return file_ + ":" + std::to_string(element.GetLineNum()) + ": " + label(element) + " " + message;
}

void Diagnostics::warn(const tinyxml2::XMLElement& element, const std::string& message) { warnings_.push_back(line(element, message)); }

void Diagnostics::warn_in(std::size_t place, const tinyxml2::XMLElement& element, const std::string& message) {
  warnings_.at(place) = line(element, message);
}

std::vector<std::string> Diagnostics::take_warnings() {
  std::vector<std::string> out = std::move(warnings_);
  warnings_.clear();
  out.erase(std::remove(out.begin(), out.end(), std::string()), out.end());  // places reserved and never filled
  return out;
}

void Diagnostics::warn_at(const tinyxml2::XMLElement& element, const char* attribute, const std::string& message) {
  SourceLocation location;
  location.file = file_;
  location.line = static_cast<std::size_t>(element.GetLineNum());
  location.field = field(element, attribute);
  warnings_.push_back(format_load_error(location, message));
}

}  // namespace curvestep::host::svg
