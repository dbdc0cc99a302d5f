// SPDX-License-Identifier: MIT
// Text from input files made safe to print: one sanitising function for every message printer.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace curvestep::host {

/// The most characters of input text a message quotes (longer text is cut and ends in "...").
inline constexpr std::size_t max_quoted_chars = 40;

/// `text` with control characters (C0, DEL, C1) and bytes that are not valid UTF-8 written as
/// \xNN (tab kept, newline as \n), so that no message can move the cursor, change colours or
/// break a terminal or an XML file. Valid UTF-8 outside the control ranges is kept as it is.
[[nodiscard]] std::string printable(std::string_view text);

/// printable(text) cut to at most `max_quoted_chars` input bytes, ending in "..." when cut: for
/// quoting a piece of input (a number, an id, a word) inside a message.
[[nodiscard]] std::string quoted_excerpt(std::string_view text);

}  // namespace curvestep::host
