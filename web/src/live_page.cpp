#include "swath/web/live_page.hpp"

#include <nlohmann/json.hpp>

namespace swath::web {
namespace {

void put_in_place(std::string& text, const std::string& placeholder, const std::string& with) {
  const std::size_t at = text.find(placeholder);
  if (at != std::string::npos) text.replace(at, placeholder.size(), with);
}

std::string escaped_html(const std::string& s) {
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

std::string page(const std::string& title, const nlohmann::ordered_json& data,
                 const std::string& csp) {
  // '<' only ever stands inside JSON strings: as \u003c no "</script>" can end the script early.
  const std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  safe.reserve(json.size());
  for (char c : json) {
    if (c == '<')
      safe += "\\u003c";
    else
      safe += c;
  }
  // From the last placeholder to the first: what is put in cannot be taken for a placeholder.
  std::string html = live_page_template();
  put_in_place(html, "/*SWATH_DATA*/", safe);
  put_in_place(html, "/*SWATH_TITLE*/", escaped_html(title));
  put_in_place(html, "/*SWATH_CSP*/", csp);
  return html;
}

const char* const kCsp =
    "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:";

}  // namespace

std::string live_page(const std::string& title) {
  return page(title, {{"title", title}, {"mode", "live"}},
              std::string(kCsp) + "; connect-src 'self'");
}

std::string replay_page(const std::string& title, const std::string& events_jsonl) {
  return page(title, {{"title", title}, {"mode", "replay"}, {"events", events_jsonl}}, kCsp);
}

}  // namespace swath::web
