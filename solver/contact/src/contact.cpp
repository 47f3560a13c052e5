#include "ugs/contact/contact.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "pair_distribution.hpp"
#include "saddle_solver.hpp"
#include "saddle_system.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/petsc_session.hpp"

// FaultContact in three parts (each in its own file): the pair distribution (which rank owns which
// node pair, the pairs' data, the twins' displacements), the saddle system (the blocks C, B, D) and
// the saddle solver (MUMPS or the field split with the augmentation). This file keeps the contact
// state of the owned pairs (multipliers, gaps, states at the iterate, the sub-step and the step),
// evaluates the contact law (the residual) and drives the three parts.
namespace ugs::contact {
namespace {

using detail::PairData;

// -ugs_contact_monitor: every node pair that changes state (stick, slip, open) in an iteration.
bool contact_monitor() {
  static const bool on = mech::petsc_option_given("-ugs_contact_monitor");
  return on;
}

std::string broadcast_string(MPI_Comm comm, std::string s) {
  unsigned long n = s.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, comm);
  s.resize(n);
  if (n) MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, 0, comm);
  return s;
}

}  // namespace

struct FaultContact::Impl {
  MPI_Comm comm;
  int rank = 0, size = 1;
  const FaultModel* fm = nullptr;
  ContactOptions opt;
  std::vector<std::string> fault_names;

  detail::PairDistribution pairs;     // owned pairs, the exchange with rank 0, the twins' displacements
  detail::SaddleSystem system;        // C, B, D
  detail::SaddlePointSolver linear;   // MUMPS or the field split

  // ---- contact state of the owned pairs -------------------------------------------------------
  int m = 0;                                  // owned pairs
  std::vector<std::array<double, 3>> lam, lam_c, lam_step, g, gc, gc_step;
  std::vector<double> dp_now, dp_c, dp_start, dp_target;  // fluid pressure change [Pa]
  std::vector<PairState> st, st_prev, st_c, st_step;
  std::vector<int> flips;
  std::vector<std::uint8_t> changed_last;
  std::vector<PairEquations> eq;
  bool settled_flag = true;

  std::vector<std::uint8_t> owned_fixed;      // prescribed components of the owned nodes
  ContactStats stats;

  int junctions = 0;  // junction groups over all ranks (PairData::junction)

  PairLaw law(int q) const {
    const PairData& d = pairs.pairs[q];
    PairLaw L;
    L.area = d.area;
    L.k = d.k;
    L.cohesion = d.cohesion;
    L.mu = d.mu;
    L.active = d.active;
    L.regularization = 0;  // the pairs closing a cycle get theirs in residual(), from their cycle's state
    return L;
  }

  // ---- setup ----------------------------------------------------------------------------------
  void setup(const mech::CouplingContext& c) {
    comm = c.comm;
    rank = c.rank;
    size = c.size;
    owned_fixed.assign(c.owned_fixed->begin(), c.owned_fixed->begin() + c.n_owned);
    std::string names;
    if (rank == 0)
      for (const auto& f : fm->faults) names += f.name + '\n';
    names = broadcast_string(comm, names);
    for (std::size_t p = 0; p < names.size();) {
      const auto e = names.find('\n', p);
      fault_names.push_back(names.substr(p, e - p));
      p = e + 1;
    }
    pairs.build(c, fm);
    m = pairs.m;
    for (int q = 0; q < m; ++q) junctions = std::max(junctions, pairs.pairs[q].junction + 1);
    MPI_Allreduce(MPI_IN_PLACE, &junctions, 1, MPI_INT, MPI_MAX, comm);

    lam.resize(m);
    for (int q = 0; q < m; ++q) lam[q] = {pairs.pairs[q].lam0[0], pairs.pairs[q].lam0[1], pairs.pairs[q].lam0[2]};
    lam_c = lam_step = lam;
    g.assign(m, {0, 0, 0});
    gc = gc_step = g;
    dp_now.assign(m, 0.0);
    dp_c = dp_start = dp_target = dp_now;
    st.assign(m, PairState::Stick);
    st_prev = st_c = st_step = st;
    flips.assign(m, 0);
    changed_last.assign(m, 0);
    eq.resize(m);

    system.create(c, pairs);
    linear.setup(c, pairs, system, opt);
  }

  // ---- residual -------------------------------------------------------------------------------
  double residual(Vec u, Vec r) {
    const PetscScalar* ua = pairs.twins(u);
    double ss = 0;
    int changes = 0;
    for (int q = 0; q < m; ++q) {
      const PairData& d = pairs.pairs[q];
      double ur[3];
      for (int k = 0; k < 3; ++k) ur[k] = ua[6 * q + 3 + k] - ua[6 * q + k];
      for (int j = 0; j < 3; ++j) g[q][j] = d.R[j] * ur[0] + d.R[3 + j] * ur[1] + d.R[6 + j] * ur[2];
      const std::array<double, 3> lam0{d.lam0[0], d.lam0[1], d.lam0[2]};
      eq[q] = pair_equations(law(q), lam[q], lam0, lam_c[q], g[q], gc[q], d.p0 + dp_now[q], st_prev[q]);
      st[q] = eq[q].state;
      changed_last[q] = st[q] != st_prev[q];
      if (changed_last[q] && contact_monitor())
        std::fprintf(stderr, "    pair %d (%.0f %.0f %.0f): %s -> %s  lam %.3e %.3e %.3e g %.3e %.3e %.3e p %.3e\n", q, d.x[0], d.x[1],
                     d.x[2], pair_state_name(st_prev[q]), pair_state_name(st[q]), lam[q][0], lam[q][1], lam[q][2], g[q][0],
                     g[q][1], g[q][2], d.p0 + dp_now[q]);
      if (changed_last[q]) ++flips[q], ++changes;
      st_prev[q] = st[q];
    }
    pairs.restore_twins(ua);
    // The pair closing a cycle: where every pair of the cycle sticks its constraint follows from the
    // others' and the weight only fixes the multipliers' circulation (contact.hpp); the states
    // above do not depend on it.
    if (junctions > 0) {
      std::vector<int> open(junctions, 0), open_all(junctions, 0);
      for (int q = 0; q < m; ++q)
        if (pairs.pairs[q].junction >= 0 && st[q] != PairState::Stick) open[pairs.pairs[q].junction] = 1;
      MPI_Allreduce(open.data(), open_all.data(), junctions, MPI_INT, MPI_MAX, comm);
      for (int q = 0; q < m; ++q) {
        const PairData& d = pairs.pairs[q];
        if (d.redundant)
          add_regularization(eq[q], open_all[d.junction] ? opt.regularization : opt.closed_regularization, d.area, lam[q], lam_c[q]);
      }
    }
    for (int q = 0; q < m; ++q)
      for (double f : eq[q].F) ss += f * f;
    stats.state_changes += changes;
    int any = 0;
    MPI_Allreduce(&changes, &any, 1, MPI_INT, MPI_SUM, comm);
    settled_flag = any == 0;
    system.subtract_coupling_force(pairs, lam, r);  // r -= C (lambda - lambda_0)
    double total = 0;
    MPI_Allreduce(&ss, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
    return total;
  }

  // ---- Newton system --------------------------------------------------------------------------
  mech::CouplingSolve solve(Mat A, Vec r, Vec du, double rtol) {
    const auto t0 = std::chrono::steady_clock::now();
    system.fill(pairs, eq);
    const mech::CouplingSolve out = linear.solve(A, r, du, rtol, pairs, system, eq, owned_fixed, lam, stats);
    ++stats.solves;
    stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  }

  // ---- messages -------------------------------------------------------------------------------
  // Lists pairs flagged on any rank: "fault 'F': nodes 12/40012 at (x, y, z), ...".
  std::string describe(const std::vector<int>& mine, const std::string& what) {
    std::string local;
    for (int q : mine) {
      const PairData& d = pairs.pairs[q];
      local += fmt::format("{}\t{}/{} at ({:.1f}, {:.1f}, {:.1f})\n", d.fault, d.tag1, d.tag2, d.x[0], d.x[1], d.x[2]);
    }
    int n = static_cast<int>(local.size());
    std::vector<int> counts(size), displs(size, 0);
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    std::string all;
    if (rank == 0) {
      for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
      all.resize(displs[size - 1] + counts[size - 1]);
    }
    MPI_Gatherv(local.data(), n, MPI_CHAR, all.data(), counts.data(), displs.data(), MPI_CHAR, 0, comm);
    std::string msg;
    if (rank == 0 && !all.empty()) {
      // Per fault: the count and the first few node pairs.
      std::vector<std::vector<std::string>> per(fault_names.size());
      for (std::size_t p = 0; p < all.size();) {
        const auto e = all.find('\n', p);
        const std::string line = all.substr(p, e - p);
        const auto tab = line.find('\t');
        per[std::stoi(line.substr(0, tab))].push_back(line.substr(tab + 1));
        p = e + 1;
      }
      for (std::size_t f = 0; f < per.size(); ++f) {
        if (per[f].empty()) continue;
        std::string list;
        for (std::size_t i = 0; i < per[f].size() && i < 6; ++i) list += (i ? ", " : "") + per[f][i];
        if (per[f].size() > 6) list += fmt::format(", ... ({} more)", per[f].size() - 6);
        msg += fmt::format("{}fault '{}': {} {} (node pairs side 1/side 2): {}", msg.empty() ? "" : "; ", fault_names[f],
                           per[f].size(), what, list);
      }
    }
    return broadcast_string(comm, msg);
  }
};

FaultContact::FaultContact(MPI_Comm comm, const FaultModel* model, const ContactOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->comm = comm;
  MPI_Comm_rank(comm, &impl_->rank);
  MPI_Comm_size(comm, &impl_->size);
  impl_->fm = model;
  impl_->opt = options;
}

FaultContact::~FaultContact() = default;

void FaultContact::setup(const mech::CouplingContext& ctx) { impl_->setup(ctx); }

void FaultContact::set_pressure_change(const std::vector<double>& dp_pairs) {
  Impl& s = *impl_;
  if (s.rank == 0 && dp_pairs.size() != s.pairs.order.size())
    throw std::logic_error("FaultContact::set_pressure_change: wrong size");
  s.pairs.scatter(dp_pairs, 1, s.dp_target.data());
}

PairResults FaultContact::gather() const {
  const Impl& s = *impl_;
  std::vector<double> lam(3 * s.m), g(3 * s.m), pf(s.m), st(s.m);
  for (int q = 0; q < s.m; ++q) {
    for (int j = 0; j < 3; ++j) lam[3 * q + j] = s.lam_c[q][j], g[3 * q + j] = s.gc[q][j];
    pf[q] = s.pairs.pairs[q].p0 + s.dp_c[q];
    st[q] = static_cast<double>(static_cast<int>(s.st_c[q]));
  }
  PairResults out;
  out.lambda = s.pairs.gather(lam, 3);
  out.g = s.pairs.gather(g, 3);
  out.p_f = s.pairs.gather(pf, 1);
  const auto sv = s.pairs.gather(st, 1);
  out.state.resize(sv.size());
  for (std::size_t i = 0; i < sv.size(); ++i) out.state[i] = static_cast<std::uint8_t>(sv[i]);
  return out;
}

FaultContact::Snapshot FaultContact::save() const {
  const Impl& s = *impl_;
  Snapshot snap;
  for (int q = 0; q < s.m; ++q) {
    snap.lambda.insert(snap.lambda.end(), s.lam_c[q].begin(), s.lam_c[q].end());
    snap.g.insert(snap.g.end(), s.gc[q].begin(), s.gc[q].end());
    snap.state.push_back(static_cast<std::uint8_t>(s.st_c[q]));
  }
  snap.dp = s.dp_c;
  return snap;
}

void FaultContact::restore(const Snapshot& snap) {
  Impl& s = *impl_;
  for (int q = 0; q < s.m; ++q) {
    for (int j = 0; j < 3; ++j) s.lam_c[q][j] = snap.lambda[3 * q + j], s.gc[q][j] = snap.g[3 * q + j];
    s.st_c[q] = static_cast<PairState>(snap.state[q]);
  }
  s.lam = s.lam_step = s.lam_c;
  s.g = s.gc_step = s.gc;
  s.st = s.st_prev = s.st_step = s.st_c;
  s.dp_c = s.dp_start = s.dp_now = s.dp_target = snap.dp;
}

FaultContact::Snapshot FaultContact::gather_snapshot() const {
  const Impl& s = *impl_;
  const Snapshot mine = save();
  std::vector<double> st(mine.state.begin(), mine.state.end());
  Snapshot all;
  all.lambda = s.pairs.gather(mine.lambda, 3);
  all.g = s.pairs.gather(mine.g, 3);
  all.dp = s.pairs.gather(mine.dp, 1);
  for (double v : s.pairs.gather(st, 1)) all.state.push_back(static_cast<std::uint8_t>(v));
  return all;
}

void FaultContact::restore_gathered(const Snapshot& all) {
  const Impl& s = *impl_;
  if (s.rank == 0 && (all.lambda.size() != 3 * all.dp.size() || all.g.size() != 3 * all.dp.size() ||
                      all.state.size() != all.dp.size() || all.dp.size() != s.pairs.order.size()))
    throw std::logic_error("FaultContact::restore_gathered: wrong sizes");
  Snapshot mine;
  mine.lambda.resize(3 * s.m);
  mine.g.resize(3 * s.m);
  mine.dp.resize(s.m);
  std::vector<double> st(s.m), st_all(all.state.begin(), all.state.end());
  s.pairs.scatter(all.lambda, 3, mine.lambda.data());
  s.pairs.scatter(all.g, 3, mine.g.data());
  s.pairs.scatter(all.dp, 1, mine.dp.data());
  s.pairs.scatter(st_all, 1, st.data());
  for (double v : st) mine.state.push_back(static_cast<std::uint8_t>(v));
  restore(mine);
}

const ContactStats& FaultContact::stats() const { return impl_->stats; }

std::string FaultContact::description() const {
  const Impl& s = *impl_;
  if (s.linear.kind() == SaddleSolver::Mumps) return fmt::format("{} node pairs, saddle point by MUMPS (LU)", s.pairs.M);
  // GAMG unless the PETSc options chose BoomerAMG (saddle_solver.cpp).
  char pc[64] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-contact_fieldsplit_u_pc_type", pc, sizeof pc, &set);
  return fmt::format("{} node pairs, saddle point by FGMRES + Schur field split ({} on the displacement block, augmentation {:g})",
                     s.pairs.M, set && std::string(pc) == "hypre" ? "BoomerAMG" : "GAMG", s.opt.augmentation);
}

std::size_t FaultContact::global_pairs() const { return static_cast<std::size_t>(impl_->pairs.M); }

void FaultContact::begin_step() {
  Impl& s = *impl_;
  s.lam_step = s.lam_c;
  s.gc_step = s.gc;
  s.st_step = s.st_c;
  s.dp_start = s.dp_c;
}

void FaultContact::begin_substep(double fraction) {
  Impl& s = *impl_;
  for (int q = 0; q < s.m; ++q) s.dp_now[q] = s.dp_start[q] + fraction * (s.dp_target[q] - s.dp_start[q]);
  s.lam = s.lam_c;
  s.st_prev = s.st_c;
  std::fill(s.flips.begin(), s.flips.end(), 0);
}

double FaultContact::residual(Vec u, Vec r) { return impl_->residual(u, r); }

bool FaultContact::settled() { return impl_->settled_flag; }

std::string FaultContact::stalled() {
  Impl& s = *impl_;
  std::vector<int> cyc;
  for (int q = 0; q < s.m; ++q)
    if (s.flips[q] >= s.opt.max_state_changes) cyc.push_back(q);
  int mine = cyc.empty() ? 0 : 1, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, s.comm);
  if (!any) return {};
  return "the contact state keeps cycling (stick <-> slip <-> open): " +
         s.describe(cyc, fmt::format("node pairs changed state {} times or more", s.opt.max_state_changes));
}

mech::CouplingSolve FaultContact::solve(Mat A, Vec r, Vec du, double rtol) { return impl_->solve(A, r, du, rtol); }

std::string FaultContact::diagnosis() {
  Impl& s = *impl_;
  // The pairs whose state changed during the iteration; failing those, the largest residuals.
  std::vector<int> changed;
  for (int q = 0; q < s.m; ++q)
    if (s.flips[q] > 0) changed.push_back(q);
  int mine = changed.empty() ? 0 : 1, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, s.comm);
  if (any) return "; contact states changing: " + s.describe(changed, "node pairs changed state during the iteration");
  std::vector<std::pair<double, int>> worst;
  for (int q = 0; q < s.m; ++q) worst.push_back({std::hypot(s.eq[q].F[0], s.eq[q].F[1], s.eq[q].F[2]), q});
  std::sort(worst.begin(), worst.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  double local_max = worst.empty() ? 0.0 : worst.front().first, global_max = 0;
  MPI_Allreduce(&local_max, &global_max, 1, MPI_DOUBLE, MPI_MAX, s.comm);
  if (!(global_max > 0)) {  // e.g. the first solve failed: say so rather than list nothing
    std::string faults;
    for (const auto& n : s.fault_names) faults += fmt::format("{}fault '{}'", faults.empty() ? "" : ", ", n);
    return "; every node pair satisfies its contact equations (" + faults + ")";
  }
  std::vector<int> top;
  for (std::size_t i = 0; i < worst.size() && i < 6; ++i)
    if (worst[i].first > 0.1 * global_max) top.push_back(worst[i].second);
  return "; largest contact residuals: " + s.describe(top, "node pairs far from equilibrium");
}

void FaultContact::commit() {
  Impl& s = *impl_;
  s.lam_c = s.lam;
  s.gc = s.g;
  s.st_c = s.st;
  s.dp_c = s.dp_now;
}

void FaultContact::revert_substep() {
  Impl& s = *impl_;
  s.lam = s.lam_c;
  s.st = s.st_prev = s.st_c;
}

void FaultContact::revert_step() {
  Impl& s = *impl_;
  s.lam = s.lam_c = s.lam_step;
  s.gc = s.gc_step;
  s.st = s.st_prev = s.st_c = s.st_step;
  s.dp_c = s.dp_start;
}

}  // namespace ugs::contact
