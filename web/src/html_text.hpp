#pragma once
// Internal to swath::web: how the pages' placeholders are filled (plan_page.cpp, live_page.cpp).

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <string>

namespace swath::web::detail {

/// What every page may load: its own inline script and style, data: images, nothing else.
inline constexpr const char* kOfflineCsp =
    "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:";

/// Replaces the first `placeholder` in `text`. The pages fill theirs from the last to the first:
/// what is put in cannot then be taken for a placeholder.
inline void replace_once(std::string& text, const std::string& placeholder,
                         const std::string& with) {
  const std::size_t at = text.find(placeholder);
  if (at != std::string::npos) text.replace(at, placeholder.size(), with);
}

/// `s` as HTML text (also inside a double-quoted attribute).
inline std::string html_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

/// `data` as a JavaScript literal for a <script> element. '<' only ever stands inside JSON
/// strings: as \u003c no "</script>" can end the script early.
inline std::string script_json(const nlohmann::ordered_json& data) {
  const std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  safe.reserve(json.size());
  for (char c : json) {
    if (c == '<')
      safe += "\\u003c";
    else
      safe += c;
  }
  return safe;
}

/// `bytes` in base64 (RFC 4648, with padding), for a data: address.
inline std::string base64(const std::string& bytes) {
  static const char* const kDigits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t k = 0; k < bytes.size(); k += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - k);
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 3; ++i)
      v = (v << 8) | (i < n ? static_cast<unsigned char>(bytes[k + i]) : 0u);
    for (std::size_t i = 0; i < 4; ++i) out += i <= n ? kDigits[(v >> (18 - 6 * i)) & 63] : '=';
  }
  return out;
}

}  // namespace swath::web::detail
