// SPDX-License-Identifier: MIT
// Internal: the CSS the importer reads — <style> sheets with simple selectors (element, .class,
// #id, *, comma lists) and style="..." attributes — and the cascade of one property:
// style attribute, then the sheet's rules (by specificity: id, class, element; later rules win
// ties), then the presentation attribute. Other selectors (descendants, attributes, pseudo-classes)
// never match; @-rules are skipped.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <tinyxml2.h>

namespace curvestep::host::svg {

/// The rules of a document's <style> sheets and the cascade of a property.
class StyleSheet {
 public:
  /// Adds the rules of one sheet's text.
  void add(std::string_view css);

  /// The cascaded value of `name` for `element` ("" if none of the three sources sets it).
  [[nodiscard]] std::string property(const tinyxml2::XMLElement& element, const std::string& name) const;

  /// How many rules were read (selectors of comma lists counted apiece).
  [[nodiscard]] std::size_t rule_count() const noexcept { return rules_.size(); }

 private:
  struct Rule {
    char kind = 0;            ///< '*', 'e' (element), '.', '#'
    std::string name;         ///< element name, class or id
    int specificity = 0;      ///< 100 id, 10 class, 1 element, 0 *
    std::size_t order = 0;    ///< position in the sheets
    std::map<std::string, std::string> declarations;
  };
  [[nodiscard]] static bool matches(const Rule& rule, const tinyxml2::XMLElement& element);
  std::vector<Rule> rules_;
};

/// The declarations of a style attribute or rule body ("a: b; c: d"), trimmed, !important dropped.
[[nodiscard]] std::map<std::string, std::string> parse_declarations(std::string_view text);

}  // namespace curvestep::host::svg
