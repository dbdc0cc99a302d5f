// SPDX-License-Identifier: MIT
// Element names and presentation properties (svg_attributes.hpp).
#include "svg_attributes.hpp"

#include <cctype>

namespace curvestep::host::svg {

std::string trim(std::string_view text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin])) != 0) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1])) != 0) --end;
  return std::string(text.substr(begin, end - begin));
}

std::string local_name(const tinyxml2::XMLElement& element) {
  std::string name = element.Name();
  if (name.rfind("svg:", 0) == 0) name = name.substr(4);
  return name;
}

std::string property(const tinyxml2::XMLElement& element, const std::string& name) {
  if (const char* style = element.Attribute("style")) {
    std::string_view rest = style;
    while (!rest.empty()) {
      const auto end = rest.find(';');
      const std::string_view declaration = rest.substr(0, end);
      const auto colon = declaration.find(':');
      if (colon != std::string_view::npos && trim(declaration.substr(0, colon)) == name) {
        return trim(declaration.substr(colon + 1));
      }
      if (end == std::string_view::npos) break;
      rest.remove_prefix(end + 1);
    }
  }
  if (const char* value = element.Attribute(name.c_str())) return trim(value);
  return {};
}

}  // namespace curvestep::host::svg
