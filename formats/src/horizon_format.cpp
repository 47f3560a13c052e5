// Which horizon format a file holds, from its first meaningful line.
#include <string>

#include "text_lines.hpp"
#include "ugs/formats/horizon_grid.hpp"

namespace ugs {

HorizonFormat detect_horizon_format(const std::string& path) {
  text::Lines in(path, "a horizon file");
  while (in.next()) {
    const auto& t = in.tokens();
    if (t.empty() || t[0].starts_with("!") || t[0].starts_with("#")) continue;
    if (t[0] == "-996") return HorizonFormat::Irap;
    if (t[0] == "FSASCI") return HorizonFormat::Cps3;
    if (t[0] == "GOCAD" && t.size() > 1 && t[1] == "TSurf") return HorizonFormat::Tsurf;
    if (t[0].starts_with("@") && in.text().find("GRID") != std::string::npos) return HorizonFormat::Zmap;
    return HorizonFormat::Unknown;
  }
  return HorizonFormat::Unknown;
}

const char* horizon_format_name(HorizonFormat f) {
  switch (f) {
    case HorizonFormat::Irap: return "IRAP classic ASCII";
    case HorizonFormat::Cps3: return "CPS-3 ASCII";
    case HorizonFormat::Zmap: return "ZMAP+";
    case HorizonFormat::Tsurf: return "GOCAD TSurf";
    case HorizonFormat::Unknown: break;
  }
  return "unknown";
}

}  // namespace ugs
