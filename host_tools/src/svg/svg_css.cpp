// SPDX-License-Identifier: MIT
// <style> sheets with simple selectors and the cascade of one property (svg_css.hpp).
#include "svg_css.hpp"

#include <sstream>

#include "svg_attributes.hpp"

namespace curvestep::host::svg {
namespace {

std::string without_comments(std::string_view css) {
  std::string out;
  std::size_t i = 0;
  while (i < css.size()) {
    if (css.substr(i, 2) == "/*") {
      const auto end = css.find("*/", i + 2);
      if (end == std::string_view::npos) break;
      i = end + 2;
      out += ' ';
    } else {
      out += css[i++];
    }
  }
  return out;
}

}  // namespace

std::map<std::string, std::string> parse_declarations(std::string_view text) {
  std::map<std::string, std::string> out;
  while (!text.empty()) {
    const auto end = text.find(';');
    const std::string_view declaration = text.substr(0, end);
    const auto colon = declaration.find(':');
    if (colon != std::string_view::npos) {
      std::string value = trim(declaration.substr(colon + 1));
      const auto important = value.find("!important");
      if (important != std::string::npos) value = trim(value.substr(0, important));
      out[trim(declaration.substr(0, colon))] = value;
    }
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return out;
}

void StyleSheet::add(std::string_view css) {
  const std::string text = without_comments(css);
  std::size_t i = 0;
  while (i < text.size()) {
    const auto open = text.find('{', i);
    if (open == std::string::npos) break;
    const std::string prelude = trim(std::string_view(text).substr(i, open - i));
    // The block's end, with nested blocks (@media { rule { } }) skipped as a whole.
    std::size_t depth = 1;
    std::size_t close = open + 1;
    for (; close < text.size() && depth > 0; ++close) {
      if (text[close] == '{') ++depth;
      if (text[close] == '}') --depth;
    }
    const std::string_view body = std::string_view(text).substr(open + 1, close - open - 2 < text.size() ? close - open - 2 : 0);
    i = close;
    if (prelude.empty() || prelude.front() == '@') continue;
    const auto declarations = parse_declarations(body);
    std::stringstream selectors(prelude);
    for (std::string selector; std::getline(selectors, selector, ',');) {
      selector = trim(selector);
      if (selector.empty()) continue;
      Rule rule;
      rule.order = rules_.size();
      rule.declarations = declarations;
      const bool simple = selector.find_first_of(" >+~[:") == std::string::npos;
      const auto marks = selector.find_first_of(".#", 1);
      if (!simple || marks != std::string::npos) continue;  // not a simple selector: never matches
      if (selector == "*") {
        rule.kind = '*';
      } else if (selector.front() == '.' || selector.front() == '#') {
        rule.kind = selector.front();
        rule.name = selector.substr(1);
        rule.specificity = selector.front() == '#' ? 100 : 10;
      } else {
        rule.kind = 'e';
        rule.name = selector;
        rule.specificity = 1;
      }
      rules_.push_back(std::move(rule));
    }
  }
}

bool StyleSheet::matches(const Rule& rule, const tinyxml2::XMLElement& element) {
  switch (rule.kind) {
    case '*': return true;
    case 'e': return local_name(element) == rule.name;
    case '#': return element.Attribute("id") != nullptr && rule.name == element.Attribute("id");
    case '.': {
      const char* classes = element.Attribute("class");
      if (classes == nullptr) return false;
      std::istringstream words(classes);
      for (std::string word; words >> word;) {
        if (word == rule.name) return true;
      }
      return false;
    }
    default: return false;
  }
}

std::string StyleSheet::property(const tinyxml2::XMLElement& element, const std::string& name) const {
  if (const char* style = element.Attribute("style")) {
    const auto declarations = parse_declarations(style);
    if (const auto found = declarations.find(name); found != declarations.end()) return found->second;
  }
  const Rule* best = nullptr;
  for (const auto& rule : rules_) {
    if (rule.declarations.count(name) == 0 || !matches(rule, element)) continue;
    if (best == nullptr || rule.specificity >= best->specificity) best = &rule;  // later rules win ties
  }
  if (best != nullptr) return best->declarations.at(name);
  if (const char* value = element.Attribute(name.c_str())) return trim(value);
  return {};
}

}  // namespace curvestep::host::svg
