// SPDX-License-Identifier: MIT
// Internal: reading element names and presentation properties (attribute or style="...").
#pragma once

#include <string>
#include <string_view>

#include <tinyxml2.h>

namespace curvestep::host::svg {

/// `text` without leading and trailing whitespace.
[[nodiscard]] std::string trim(std::string_view text);

/// The element name without an "svg:" prefix.
[[nodiscard]] std::string local_name(const tinyxml2::XMLElement& element);

/// The value of a presentation property from the style attribute or the attribute itself ("" if neither).
[[nodiscard]] std::string property(const tinyxml2::XMLElement& element, const std::string& name);

}  // namespace curvestep::host::svg
