// SPDX-License-Identifier: MIT
// The transform attribute about the transform-origin (svg_transform.hpp).
#include "svg_transform.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "svg_attributes.hpp"

namespace curvestep::host::svg {
namespace {

bool horizontal_keyword(const std::string& word) { return word == "left" || word == "right"; }
bool vertical_keyword(const std::string& word) { return word == "top" || word == "bottom"; }

}  // namespace

Point2 transform_origin(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const std::string& text,
                        const LengthContext& context) {
  std::vector<std::string> words;
  std::istringstream stream(text);
  for (std::string word; stream >> word;) words.push_back(word);
  auto bad = [&](const std::string& why) -> Point2 {
    diagnostics.fail(element, "transform-origin", why + ", got \"" + text + "\"");
  };
  if (words.empty() || words.size() > 3) bad("expected one to three values (keywords left, center, right, top, bottom or lengths)");
  if (words.size() == 3 && words[2].back() == '%') bad("the third value (z) must be a length");
  if (words.size() == 3) (void)length_value(diagnostics, element, "transform-origin", words[2], context, LengthAxis::Other);
  std::string x_word = words[0];
  std::string y_word = words.size() >= 2 ? words[1] : "center";
  if (words.size() == 1 && vertical_keyword(x_word)) std::swap(x_word, y_word);                   // "top" = "center top"
  if (words.size() >= 2 && (vertical_keyword(x_word) || horizontal_keyword(y_word))) std::swap(x_word, y_word);  // "top left"
  if (vertical_keyword(x_word) || horizontal_keyword(y_word)) bad("the keywords do not name one horizontal and one vertical position");
  auto resolve = [&](const std::string& word, LengthAxis axis) {
    const double side = axis == LengthAxis::X ? context.viewport_width : context.viewport_height;
    const bool keyword = word == "left" || word == "top" || word == "center" || word == "right" || word == "bottom";
    if (keyword && word != "left" && word != "top" && !(side > 0)) {
      diagnostics.fail(element, "transform-origin", "\"" + word + "\" needs the viewport's size, and the root <svg> gives none");
    }
    if (word == "left" || word == "top") return 0.0;
    if (word == "center") return side / 2;
    if (word == "right" || word == "bottom") return side;
    return length_value(diagnostics, element, "transform-origin", word, context, axis);
  };
  return {resolve(x_word, LengthAxis::X), resolve(y_word, LengthAxis::Y)};
}

Affine with_transform(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const Affine& parent,
                      const LengthContext& context) {
  const char* raw = element.Attribute("transform");
  if (raw == nullptr) return parent;
  Affine transform;
  try {
    transform = parse_transform(raw);
  } catch (const SyntaxError& error) {
    diagnostics.fail_syntax(element, "transform", error);
  }
  const std::string origin_text = property(element, "transform-origin");
  if (origin_text.empty()) return parent * transform;
  const Point2 o = transform_origin(diagnostics, element, origin_text, context);
  return parent * Affine{1, 0, 0, 1, o.x, o.y} * transform * Affine{1, 0, 0, 1, -o.x, -o.y};
}

}  // namespace curvestep::host::svg
