// The ensemble's pictures, from an ugs-ensemble output folder (docs/ensemble.md): a tornado chart
// of the sensitivity indices (sobol.csv: S1 and ST with their intervals; morris.csv: mu* and sigma)
// and fan charts of the PS series (ps_series.csv: the P10-P90 band and P50 of the members against
// the InSAR series), with the exceedance probabilities of chi as headlines. The CSVs are copied to
// the work folder as they are: the figures plot exactly the files people read.
#include <filesystem>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"

namespace ugs::report {

namespace fs = std::filesystem;

namespace {

void copy_table(const CsvTable& t, const std::string& to) {
  CsvWriter w(to, t.columns());
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t k = 0; k < t.columns().size(); ++k) w.text(t.text(r, k));
    w.end_row();
  }
  w.commit();
}

}  // namespace

void build_ensemble(Context& c) {
  if (c.opt.ensemble.empty()) return;
  const fs::path dir(c.opt.ensemble);
  const CsvTable members = CsvTable::read((dir / "members.csv").string());
  std::size_t ok = 0;
  for (std::size_t r = 0; r < members.rows(); ++r) ok += members.text(r, members.column("status")) == "ok";
  c.headlines.push_back({"ensemble", "members in the statistics", fmt::format("{} of {}", ok, members.rows()), ""});
  if (fs::exists(dir / "exceedance.csv")) {
    const CsvTable ex = CsvTable::read((dir / "exceedance.csv").string());
    for (std::size_t r = 0; r < ex.rows(); ++r)
      c.headlines.push_back({"ensemble", fmt::format("P(chi >= 0.8), P(chi >= 1) on {}", ex.text(r, ex.column("fault"))),
                             fmt::format("{:.2f}, {:.2f}", ex.number(r, ex.column("p_chi_ge_0.8")), ex.number(r, ex.column("p_chi_ge_1"))),
                             ""});
  }
  for (const char* method : {"sobol", "morris"}) {
    const fs::path p = dir / (std::string(method) + ".csv");
    if (!fs::exists(p)) continue;
    const CsvTable t = CsvTable::read(p.string());
    if (t.rows() == 0) continue;
    copy_table(t, c.work_file(std::string("ensemble_") + method + ".csv"));
    Figure f;
    f.kind = "tornado";
    f.png = std::string("ensemble_tornado_") + method + ".png";
    f.title = std::string(method) == "sobol" ? "Which parameter decides it: Sobol' indices" : "Which parameter decides it: Morris screening";
    f.caption = std::string(method) == "sobol"
                    ? "First-order (S1) and total (ST) Sobol' indices of each metric with their 95 % intervals (sobol.csv)."
                    : "Morris mean absolute elementary effect mu* and its spread sigma of each metric (morris.csv).";
    f.json = fmt::format("\"csv\": {}, \"method\": {}", jwork(std::string("ensemble_") + method + ".csv"), jstr(method));
    c.add(f);
  }
  if (fs::exists(dir / "ps_series.csv")) {
    const CsvTable t = CsvTable::read((dir / "ps_series.csv").string());
    if (t.rows() > 0) {
      copy_table(t, c.work_file("ensemble_ps_series.csv"));
      Figure f;
      f.kind = "fan";
      f.png = "ensemble_fan_ps.png";
      f.title = "PS series: the ensemble's P10-P90 band and P50 against InSAR";
      f.caption = "Simulated vertical displacement at the PS points (relative to the first PS date; band P10-P90, line "
                  "P50) with the measured series shifted to the same zero (ps_series.csv).";
      f.json = fmt::format("\"csv\": {}", jwork("ensemble_ps_series.csv"));
      c.add(f);
    }
  }
}

}  // namespace ugs::report
