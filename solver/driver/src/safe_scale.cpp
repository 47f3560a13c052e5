#include "ugs/driver/safe_scale.hpp"

#include <algorithm>

namespace ugs::driver {

void Watch::see(const contact::FaultModel& fm, const contact::FaultFields& f, const std::string& d) {
  for (std::size_t q = 0; q < fm.pairs.size(); ++q) {
    if (!fm.pairs[q].frictional()) continue;
    const bool hit = f.state[q] != 0 || f.chi[q] >= 1 - 1e-9;
    if (f.chi[q] > max_chi) max_chi = f.chi[q];
    if (hit && !critical) {
      critical = true;
      limiter = Limiter::FaultChi;
      fault = fm.faults[fm.pairs[q].fault].name;
      date = d;
      at = fm.pairs[q].x;
    }
  }
}

std::string limiter_text(Limiter l) {
  switch (l) {
    case Limiter::FaultChi: return "fault chi = 1";
    case Limiter::CaprockTensile: return "caprock tensile failure";
    case Limiter::CaprockShear: return "caprock shear failure";
    case Limiter::None: break;
  }
  return "";
}

void Watch::see(const CaprockStep& st, const std::string& d) {
  min_tensile_margin = std::min(min_tensile_margin, st.tensile.margin_Pa);
  min_shear_margin = std::min(min_shear_margin, st.shear.margin_Pa);
  if (critical) return;
  // Tension first at one step: an open fracture is the more direct loss of the seal.
  const CaprockWorst* w = st.tensile_failure() ? &st.tensile : st.shear_failure() ? &st.shear : nullptr;
  if (!w) return;
  critical = true;
  limiter = st.tensile_failure() ? Limiter::CaprockTensile : Limiter::CaprockShear;
  seal = w->material;
  date = d;
  at = w->at;
}

std::string Watch::what() const {
  if (limiter == Limiter::FaultChi) return "fault " + fault + " first reaches chi = 1";
  if (limiter != Limiter::None) return "seal " + seal + " fails first (" + limiter_text(limiter) + ")";
  return "";
}

SafeScale search_safe_scale(double max_scale, double tolerance, const std::function<Watch(double)>& trial) {
  SafeScale safe;
  double lo = 0, hi = -1;
  Watch lo_w, hi_w;
  for (double s = 1;; s = std::min(2 * s, max_scale)) {
    const Watch w = trial(s);
    if (w.critical) {
      hi = s, hi_w = w;
      break;
    }
    lo = s, lo_w = w;
    if (s >= max_scale) break;
  }
  if (hi > 0) {
    while (hi - lo > tolerance * hi) {
      const double mid = 0.5 * (lo + hi);
      const Watch w = trial(mid);
      if (w.critical) hi = mid, hi_w = w;
      else lo = mid, lo_w = w;
    }
    safe.found = true;
    safe.critical = hi;
    safe.first = hi_w;
  }
  safe.safe = lo;
  safe.peak_dp_max = lo_w.dp_max;
  safe.peak_dp_min = lo_w.dp_min;
  return safe;
}

void scale_about(std::vector<double>& dp, const std::vector<double>& ref, double s) {
  for (std::size_t i = 0; i < dp.size(); ++i) dp[i] = ref[i] + s * (dp[i] - ref[i]);
}

}  // namespace ugs::driver
