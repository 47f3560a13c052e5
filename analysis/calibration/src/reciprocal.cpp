#include "ugs/calibration/reciprocal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::calibration {

using runner::ParameterSpec;

namespace {

constexpr int kGrid = 400;      // intervals of the 1/x range on which the model's local minima are sought
constexpr int kProfile = 40;    // intervals of the modelled misfit profile reported

using Weights = std::array<double, 3>;

// sum_k w_k s_k, value by value (the three series share points and dates).
SimulatedSeries combination(const std::array<const SimulatedSeries*, 3>& s, const Weights& w) {
  SimulatedSeries out;
  out.ids = s[0]->ids;
  out.times = s[0]->times;
  out.enu.resize(s[0]->enu.size());
  for (std::size_t i = 0; i < out.enu.size(); ++i) out.enu[i] = w[0] * s[0]->enu[i] + w[1] * s[1]->enu[i] + w[2] * s[2]->enu[i];
  return out;
}

// The series quadratic in y through the three runs (Lagrange weights, summing to 1), and the mean
// square misfit of that series as a quartic in y: with R_k the residual vector of run k in the
// misfit's quadratic form Q, Q(sum_k l_k R_k) = sum_jk l_j l_k <R_j, R_k>, and by polarisation
// <R_j, R_k> = 2 Q((R_j + R_k) / 2) - (Q(R_j) + Q(R_k)) / 2 (the measured series enter R with
// weight 1 since the weights sum to 1, so (R_j + R_k) / 2 is the residual of the averaged series).
struct QuarticModel {
  Weights y{};                                // the runs' 1/x
  std::array<std::array<double, 3>, 3> g{};   // <R_j, R_k> (mm^2)

  Weights weights(double t) const {
    Weights l;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      l[k] = (t - y[a]) * (t - y[b]) / ((y[k] - y[a]) * (y[k] - y[b]));
    }
    return l;
  }
  Weights slopes(double t) const {
    Weights d;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      d[k] = (2 * t - y[a] - y[b]) / ((y[k] - y[a]) * (y[k] - y[b]));
    }
    return d;
  }
  double form(const Weights& u, const Weights& v) const {
    double s = 0;
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) s += u[j] * g[j][k] * v[k];
    return s;
  }
  double mean_square(double t) const {
    const Weights l = weights(t);
    return form(l, l);
  }
  double slope(double t) const { return 2 * form(slopes(t), weights(t)); }
};

double square(double v) { return v * v; }

}  // namespace

void check_reciprocal(const std::vector<ParameterSpec>& params, const OptimizerOptions& o, bool scan_given) {
  if (params.size() != 1)
    throw InputError("response model",
                     fmt::format("reciprocal calibrates one parameter, {} were given (expected one parameter to calibrate; "
                                 "several paths sharing one value are one)",
                                 params.size()));
  const ParameterSpec& p = params.front();
  if (!(p.lower > 0))
    throw InputError("response model", fmt::format("reciprocal needs positive bounds, parameter to calibrate {} has lower bound {} "
                                                   "(expected 0 < LOWER < UPPER: the model is in 1/x)",
                                                   p.name, p.lower));
  if (p.log_scale)
    throw InputError("response model", fmt::format("reciprocal searches in 1/x, parameter to calibrate {} asks for :log "
                                                   "(expected LOWER:UPPER without :log)",
                                                   p.name));
  if (scan_given)
    throw InputError("response model", "reciprocal makes its own three runs (expected no scan values per parameter)");
  if (o.max_evals < 4)
    throw InputError("response model", fmt::format("reciprocal needs 4 evaluations, the evaluation budget is {} (expected at least 4)",
                                                   o.max_evals));
}

ReciprocalResult calibrate_reciprocal(Evaluator& ev, const std::vector<ParameterSpec>& params, const OptimizerOptions& o) {
  check_reciprocal(params, o, false);
  const ParameterSpec& p = params.front();
  ReciprocalResult out;
  OptimizerResult& res = out.result;
  ReciprocalReport& rep = out.report;
  const std::size_t first = ev.history().size();
  const double y_lo = 1.0 / p.upper, y_hi = 1.0 / p.lower;
  rep.x = {p.lower, 1.0 / (0.5 * (y_lo + y_hi)), p.upper};
  const auto design = ev.evaluate({{rep.x[0]}, {rep.x[1]}, {rep.x[2]}}, "reciprocal");
  for (int k = 0; k < 3; ++k) rep.rms_mm[k] = design[k].misfit.rms_mm;
  const double best_design = std::min({rep.rms_mm[0], rep.rms_mm[1], rep.rms_mm[2]});
  // 1/x of a value evaluated, exactly as the runs give it: the range's ends are the bounds.
  auto x_of = [&](double y) { return y == y_lo ? p.upper : y == y_hi ? p.lower : 1.0 / y; };

  // Brent in y inside the evaluated points next to the best, with the rest of the budget.
  auto fall_back = [&](const std::string& why) {
    rep.fallback = why;
    res.method = "reciprocal response + Brent";
    std::vector<std::pair<double, double>> pts;  // (y, rms)
    for (std::size_t i = first; i < ev.history().size(); ++i) pts.emplace_back(1.0 / ev.history()[i].x[0], ev.history()[i].misfit.rms_mm);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end(), [](const auto& u, const auto& v) { return u.first == v.first; }), pts.end());
    const std::size_t b = static_cast<std::size_t>(
        std::min_element(pts.begin(), pts.end(), [](const auto& u, const auto& v) { return u.second < v.second; }) - pts.begin());
    const double a = b > 0 ? pts[b - 1].first : pts[b].first, c = b + 1 < pts.size() ? pts[b + 1].first : pts[b].first;
    const int budget = o.max_evals - static_cast<int>(ev.history().size() - first);
    if (budget <= 0 || !(a < c)) {
      res.converged = false;
      res.stop_reason = why + "; no evaluation left for Brent (evaluation budget)";
      return;
    }
    const auto br = brent_minimize([&](double y) { return ev.evaluate({{x_of(y)}}, "brent").front().misfit.rms_mm; }, a, c,
                                   pts[b].first, pts[b].second, o.xtol * (y_hi - y_lo), budget);
    res.converged = br.converged;
    res.stop_reason = why + "; Brent: " + (br.converged ? fmt::format("bracket below xtol {} of the 1/x range", o.xtol)
                                                       : std::string("evaluation budget used"));
  };

  // The model: the three series on common points and dates, and the misfit's form between them.
  const std::array<const SimulatedSeries*, 3> s{&ev.series_of(design[0]), &ev.series_of(design[1]), &ev.series_of(design[2])};
  const bool common = s[0]->ids == s[1]->ids && s[0]->ids == s[2]->ids && s[0]->times == s[1]->times &&
                      s[0]->times == s[2]->times && s[0]->enu.size() == s[1]->enu.size() && s[0]->enu.size() == s[2]->enu.size();
  if (!common) {
    fall_back("the three runs' series differ in points or dates (no model)");
  } else {
    QuarticModel m;
    for (int k = 0; k < 3; ++k) m.y[k] = 1.0 / rep.x[k];
    m.y[0] = y_hi;
    m.y[2] = y_lo;
    for (int k = 0; k < 3; ++k) m.g[k][k] = square(rep.rms_mm[k]);
    for (int j = 0; j < 3; ++j)
      for (int k = j + 1; k < 3; ++k) {
        Weights w{0, 0, 0};
        w[j] = w[k] = 0.5;
        m.g[j][k] = m.g[k][j] = 2 * square(ev.misfit_of(combination(s, w)).rms_mm) - 0.5 * (m.g[j][j] + m.g[k][k]);
      }
    // How far from reciprocal: the middle run against the chord in y of the outer two.
    rep.curvature_mm = 0;
    rep.response_mm = 0;
    const double f = (m.y[1] - m.y[0]) / (m.y[2] - m.y[0]);
    for (std::size_t i = 0; i < s[0]->enu.size(); ++i) {
      const double a = s[0]->enu[i], b = s[1]->enu[i], c = s[2]->enu[i];
      if (std::isnan(a) || std::isnan(b) || std::isnan(c)) continue;
      rep.curvature_mm = std::max(rep.curvature_mm, 1e3 * std::abs(b - (a + f * (c - a))));
      rep.response_mm = std::max(rep.response_mm, 1e3 * std::abs(c - a));
    }
    for (int i = 0; i <= kProfile; ++i) {
      const double t = i == kProfile ? y_hi : y_lo + (y_hi - y_lo) * i / kProfile;
      rep.profile.push_back({x_of(t), std::sqrt(std::max(0.0, m.mean_square(t)))});
    }
    std::reverse(rep.profile.begin(), rep.profile.end());  // increasing x
    // Local minima of the quartic on the range: the ends where it rises inward, and the roots of its
    // slope going from - to + (bisected to round-off).
    std::vector<double> t(kGrid + 1), slope(kGrid + 1), ms(kGrid + 1);
    for (int i = 0; i <= kGrid; ++i) {
      t[i] = i == kGrid ? y_hi : y_lo + (y_hi - y_lo) * i / kGrid;
      slope[i] = m.slope(t[i]);
      ms[i] = m.mean_square(t[i]);
    }
    const double ms_max = *std::max_element(ms.begin(), ms.end()), ms_min = *std::min_element(ms.begin(), ms.end());
    std::vector<double> minima;
    if (slope[0] > 0) minima.push_back(y_lo);
    for (int i = 0; i < kGrid; ++i)
      if (slope[i] < 0 && slope[i + 1] >= 0) {
        double lo = t[i], hi = t[i + 1];
        for (int it = 0; it < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * hi; ++it) {
          const double mid = 0.5 * (lo + hi);
          (m.slope(mid) < 0 ? lo : hi) = mid;
        }
        minima.push_back(m.mean_square(lo) <= m.mean_square(hi) ? lo : hi);
      }
    if (slope[kGrid] < 0) minima.push_back(y_hi);
    if (!(ms_max - ms_min > 1e-12 * ms_max)) {
      rep.fallback = "the misfit does not change over the range (the parameter does not act on it)";
      res.method = "reciprocal response";
      res.converged = false;
      res.stop_reason = rep.fallback;
    } else if (minima.size() != 1) {
      fall_back(fmt::format("the modelled misfit has {} local minima over the range (the response is far from reciprocal)",
                            minima.size()));
    } else {
      const double y_star = minima.front();
      rep.x_model = x_of(y_star);
      rep.predicted_rms_mm = std::sqrt(std::max(0.0, m.mean_square(y_star)));
      // The model's series there, through the misfit itself: the form must be what the model assumes.
      const double direct = square(ev.misfit_of(combination(s, m.weights(y_star))).rms_mm);
      const double scale = std::max({m.g[0][0], m.g[1][1], m.g[2][2]});
      if (std::abs(direct - m.mean_square(y_star)) > 1e-9 * scale) {
        fall_back(fmt::format("the misfit is not a quadratic form of the series (the model predicts {:.6g} mm^2 at {} = {:.6g}, the "
                              "misfit of its series is {:.6g} mm^2)",
                              m.mean_square(y_star), p.name, rep.x_model, direct));
      } else {
        rep.checked_rms_mm = ev.evaluate({{rep.x_model}}, "check").front().misfit.rms_mm;
        rep.check_is_new_point = std::none_of(rep.x.begin(), rep.x.end(), [&](double v) { return v == rep.x_model; });
        if (rep.checked_rms_mm > best_design) {
          fall_back(fmt::format("the check at {} = {:.6g} (RMS {:.4f} mm, predicted {:.4f} mm) is worse than the best of the three runs "
                                "({:.4f} mm)",
                                p.name, rep.x_model, rep.checked_rms_mm, rep.predicted_rms_mm, best_design));
        } else {
          res.method = "reciprocal response";
          res.converged = true;
          res.stop_reason = fmt::format("model minimum checked by one run: RMS {:.4f} mm, predicted {:.4f} mm", rep.checked_rms_mm,
                                        rep.predicted_rms_mm);
        }
      }
    }
  }
  // The answer is the best point evaluated.
  take_best_evaluated(ev, first, res);
  return out;
}

}  // namespace ugs::calibration
