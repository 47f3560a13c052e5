#include "ugs/fem/material_point.hpp"

#include <cmath>
#include <stdexcept>

namespace ugs::fem {

void Material::finalize() {
  const std::string why = ti_check(ratios);
  if (!why.empty()) throw std::invalid_argument(why);
  if (!(biot >= 0 && biot <= 1)) throw std::invalid_argument("Biot coefficient must lie in [0, 1]");
  if (law == Law::Linear && !(E_z > 0)) throw std::invalid_argument("linear law needs a positive E");
  if (law != Law::Linear) {
    if (!(hypo.a > 0)) throw std::invalid_argument("compressibility law: a must be positive");
    if (!std::isfinite(hypo.b)) throw std::invalid_argument("compressibility law: b must be finite");
    if (!(hypo.sigma_min > 0)) throw std::invalid_argument("sigma_z_min must be positive");
  }
  if (law == Law::Hypoplastic && !(hypo.c_R > 0)) throw std::invalid_argument("c_R must be positive");
  Dhat = ti_constitutive_matrix(ti_kappa(ratios), ratios);
  if (law == Law::Linear) D_linear = ti_constitutive_matrix(E_z, ratios);
}

Mat6 Material::elastic_D(double s0) const {
  const double c = hypo.cm(s0) * 1e-6;  // 1/Pa
  Mat6 D;
  for (int i = 0; i < 36; ++i) D[i] = Dhat[i] / c;
  return D;
}

PointUpdate hypo_update(const Material& m, const PointState& st, double s0, const Vec6& eps, int guess, Hold hold,
                        TangentForm form) {
  Vec6 de;
  for (int i = 0; i < 6; ++i) de[i] = eps[i] - st.eps[i];
  const Vec6 Dde = mat_vec(m.Dhat, de);
  const double J = -Dde[ZZ];
  const HypoResult h = hypo_integrate(m.hypo, st.hypo, s0, J, guess, hold);
  PointUpdate u;
  u.J = J;
  u.J_knee = h.J_knee;
  const double inv_sec = 1e6 / h.c_secant, inv_tan = 1e6 / h.c_tangent;  // Pa
  for (int i = 0; i < 6; ++i) u.dsig[i] = st.dsig[i] + Dde[i] * inv_sec;
  // dsig = Dhat de / c_sec(J), J = -(Dhat de)_zz: d(1/c_sec)/dJ = (1/c_tan - 1/c_sec) / J, so the
  // derivative adds the rank-one term -g/J (Dhat de) (x) Dhat_zz,: . It is not symmetric unless the
  // strain increment is oedometric (Dhat de parallel to Dhat_:,zz, with Dhat_zz,zz = 1), which is
  // the symmetric form's rank-one term g Dhat_:,zz (x) Dhat_zz,: . (g -> 0 as J -> 0 on a branch.)
  u.c_tangent = h.c_tangent;
  u.c_secant = h.c_secant;
  const double g = inv_tan - inv_sec;
  if (form == TangentForm::Consistent && J != 0) {
    const double k = -g / J;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) u.Dt[6 * i + j] = m.Dhat[6 * i + j] * inv_sec + k * Dde[i] * m.Dhat[6 * ZZ + j];
  } else {
    u.Dt = symmetric_tangent(m, u);
  }
  u.phase = h.phase;
  u.hypo = h.state;
  u.saturated = h.saturated;
  return u;
}

Mat6 symmetric_tangent(const Material& m, const PointUpdate& u) {
  const double inv_sec = 1e6 / u.c_secant, g = 1e6 / u.c_tangent - inv_sec;
  Mat6 D;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) D[6 * i + j] = m.Dhat[6 * i + j] * inv_sec + g * m.Dhat[6 * i + ZZ] * m.Dhat[6 * j + ZZ];
  return D;
}

}  // namespace ugs::fem
