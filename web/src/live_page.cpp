#include "swath/web/live_page.hpp"

#include <nlohmann/json.hpp>

#include "html_text.hpp"

namespace swath::web {
namespace {

std::string page(const std::string& title, const nlohmann::ordered_json& data,
                 const std::string& csp) {
  // From the last placeholder to the first: what is put in cannot be taken for a placeholder.
  std::string html = live_page_template();
  detail::replace_once(html, "/*SWATH_DATA*/", detail::script_json(data));
  detail::replace_once(html, "/*SWATH_TITLE*/", detail::html_text(title));
  detail::replace_once(html, "/*SWATH_CSP*/", csp);
  return html;
}

}  // namespace

std::string live_page(const std::string& title, const std::optional<MapOrigin>& origin) {
  nlohmann::ordered_json data = {{"title", title}, {"mode", "live"}};
  if (origin) data["origin"] = {{"lat_deg", origin->lat_deg}, {"lon_deg", origin->lon_deg}};
  return page(title, data, std::string(detail::kOfflineCsp) + "; connect-src 'self'");
}

std::string replay_page(const std::string& title, const std::string& events_jsonl) {
  return page(title, {{"title", title}, {"mode", "replay"}, {"events", events_jsonl}},
              detail::kOfflineCsp);
}

}  // namespace swath::web
