#include "remedy_text.hpp"

namespace swath::apps {

using base::Remedy;

std::string with_remedies(const std::string& what, const std::vector<Remedy>& remedies) {
  std::string text = what;
  std::vector<std::string> phrases;
  for (const Remedy r : remedies) {
    switch (r) {
      // Those that end the sentence they belong to.
      case Remedy::far_home:
        text += " unless --far-home is given";
        break;
      case Remedy::far_home_limit:
        text += " even with --far-home";
        break;
      case Remedy::local_csv:
        text += " (or use --local for x,y metres)";
        break;
      // Those listed after it: "; a, b, or c".
      case Remedy::add_drones_or_battery:
        phrases.push_back("add drones or battery");
        break;
      case Remedy::allow_partial:
        phrases.push_back("give --allow-partial");
        break;
      case Remedy::repair:
        phrases.push_back(
            "'swath classify' names the edges; fix the vertex order, or give --repair to plan the "
            "areas it encloses");
        break;
      case Remedy::concave_hull:
        phrases.push_back("use --concave hull");
        break;
      case Remedy::simplify_zones:
        phrases.push_back("merge or simplify them");
        break;
      case Remedy::lower_clearance:
        phrases.push_back("lower --clearance or --boundary-clearance");
        break;
      case Remedy::origin:
        phrases.push_back("give --origin LAT,LON to place it on the map");
        break;
      case Remedy::sorties:
        phrases.push_back("cut the flights into sorties with --sorties auto");
        break;
      case Remedy::higher_altitude:
        phrases.push_back("fly higher with a larger --altitude (fewer lines)");
        break;
      case Remedy::endurance:
        phrases.push_back("give --endurance S, or endurance_s for the drone in the fleet file");
        break;
    }
  }
  for (std::size_t k = 0; k < phrases.size(); ++k)
    text += (k == 0 ? "; " : k + 1 == phrases.size() ? ", or " : ", ") + phrases[k];
  return text;
}

}  // namespace swath::apps
