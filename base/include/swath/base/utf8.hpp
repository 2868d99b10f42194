#pragma once
// Names from users' files and command lines are bytes: make them valid UTF-8 before they reach
// JSON, KML or a terminal.

#include <string>
#include <string_view>

namespace swath::base {

/// `text` with every byte sequence that is not valid UTF-8 (RFC 3629: no overlongs, no
/// surrogates, at most U+10FFFF) replaced by U+FFFD; valid text is returned unchanged.
std::string valid_utf8(std::string_view text);

}  // namespace swath::base
