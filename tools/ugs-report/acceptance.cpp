// The case's acceptance thresholds ([report] in the case file, docs/insar-and-reports.md "A report
// for the field"): each one given is checked against what the report measured — the largest uplift
// and settlement over the phases, the largest fault chi over the faults table (else over the
// pictured dates), the seals' smallest margins — and stated as a headline: pass or FAIL, with the
// number and where it was found. A threshold whose quantity the inputs do not give is "not checked".
#include <fmt/format.h>

#include "report.hpp"

namespace ugs::report {

void build_acceptance(Context& c) {
  if (!c.cs || !c.cs->report) return;
  const ReportSpec& r = *c.cs->report;
  struct Check {
    const char* key;
    const std::optional<double>& limit;
    bool upper;  // the measure must stay at or below the limit (else at or above)
    const char* what;
    const char* unit;
  };
  const Check checks[] = {
      {"uplift_max_mm", r.uplift_max_mm, true, "largest uplift over a phase", "mm"},
      {"settlement_max_mm", r.settlement_max_mm, true, "largest settlement over a phase", "mm"},
      {"chi_max", r.chi_max, true, "largest fault chi", ""},
      {"tensile_margin_min_MPa", r.tensile_margin_min_MPa, false, "smallest seal tensile margin", "MPa"},
      {"shear_margin_min_MPa", r.shear_margin_min_MPa, false, "smallest seal shear margin", "MPa"},
  };
  int failed = 0, checked = 0;
  for (const Check& k : checks) {
    if (!k.limit) continue;
    const std::string unit = *k.unit ? std::string(" ") + k.unit : "";
    const std::string quantity = fmt::format("{} {} {:g}{}", k.what, k.upper ? "<=" : ">=", *k.limit, unit);
    const auto it = c.measures.find(k.key);
    if (it == c.measures.end()) {
      c.headlines.push_back({"acceptance", quantity, "not checked: the inputs do not give it", ""});
      continue;
    }
    const Measure& m = it->second;
    const bool pass = k.upper ? m.value <= *k.limit : m.value >= *k.limit;
    ++checked;
    failed += pass ? 0 : 1;
    c.headlines.push_back({"acceptance", quantity, fmt::format("{:.3g}{} ({}): {}", m.value, unit, m.where, pass ? "pass" : "FAIL"), ""});
  }
  if (checked > 0)
    c.headlines.push_back({"acceptance", "thresholds of the case",
                           failed == 0 ? fmt::format("all {} pass", checked) : fmt::format("{} of {} FAIL", failed, checked), ""});
}

}  // namespace ugs::report
