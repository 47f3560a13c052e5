#include "ugs/contact/run_faulted.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/fault_output.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/mechanics/step_output.hpp"

namespace ugs::contact {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Everything only rank 0 holds.
struct Root {
  Mesh* mesh = nullptr;
  CaseFile* cs = nullptr;
  mech::Model model;
  FaultModel fm;
  std::unique_ptr<mech::PressureHistory> history;
  std::set<std::string> fields;
  Mesh top_mesh;
  std::unique_ptr<FieldSeriesWriter> results, top;
  std::unique_ptr<CsvWriter> top_csv;
  std::unique_ptr<FaultOutput> faults;
  std::vector<double> ref_cell, ref_node;  // pressure change at the reference date
  mech::SavedState snapshot;
};

struct Settings {
  int linear = 0, partition = 0, max_newton = 25, max_substeps = 64, reuse = 1, fault_solver = 0, search = 0;
  double tolerance = 1e-8, scale = 1, max_scale = 10, scale_tolerance = 0.01, ref_time = -INFINITY;
};

Mesh make_top_mesh(const Mesh& mesh, const mech::Model& model) {
  Mesh top;
  std::vector<std::uint32_t> local(mesh.num_nodes(), 0);
  for (auto v : model.top_nodes) local[v] = top.add_node(mesh.nodes[v], mesh.node_tags[v]);
  const int e = top.entity_for_physical(2, "bnd:top");
  auto& b = top.block(2, e, ElementType::Triangle);
  for (const auto& t : model.top_triangles) {
    const std::uint32_t n[3] = {local[t[0]], local[t[1]], local[t[2]]};
    top.add_element(b, n);
  }
  top.update_entity_bboxes();
  return top;
}

std::vector<std::string> broadcast_strings(MPI_Comm comm, std::vector<std::string> v) {
  std::string all;
  for (const auto& s : v) all += s + '\n';
  mech::broadcast(comm, all);
  v.clear();
  for (std::size_t p = 0; p < all.size();) {
    const auto q = all.find('\n', p);
    v.push_back(all.substr(p, q - p));
    p = q + 1;
  }
  return v;
}

// dp about the reference: ref + s (dp - ref).
void scale_about(std::vector<double>& dp, const std::vector<double>& ref, double s) {
  for (std::size_t i = 0; i < dp.size(); ++i) dp[i] = ref[i] + s * (dp[i] - ref[i]);
}

// The first patch at chi = 1 after the reference date, and the largest chi seen.
struct Watch {
  double max_chi = 0;
  bool critical = false;
  std::string fault, date;
  Point3 at{};
  double dp_max = 0, dp_min = 0;

  void see(const FaultModel& fm, const FaultFields& f, const std::string& d) {
    for (std::size_t q = 0; q < fm.pairs.size(); ++q) {
      if (!fm.pairs[q].frictional()) continue;
      const bool hit = f.state[q] != 0 || f.chi[q] >= 1 - 1e-9;
      if (f.chi[q] > max_chi) max_chi = f.chi[q];
      if (hit && !critical) {
        critical = true;
        fault = fm.faults[fm.pairs[q].fault].name;
        date = d;
        at = fm.pairs[q].x;
      }
    }
  }
};

}  // namespace

mech::RunSummary run_faulted(MPI_Comm comm, const mech::RunOptions& o, const FaultedRunOptions& fo, Mesh* mesh, CaseFile* cs,
                             SafeScale* safe_out) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  auto log = [&](int level, const std::string& s) {
    if (rank == 0 && o.log) o.log(level, s);
  };
  mech::RunSummary sum;
  const std::string stem = mech::output_stem(o.output);
  const std::string top_path = o.top.empty() ? stem + "_top.h5" : o.top;
  const std::string fault_path = fo.fault_output.empty() ? stem + "_faults.h5" : fo.fault_output;
  const std::string fault_csv = fo.fault_csv.empty() ? stem + "_faults.csv" : fo.fault_csv;
  const std::string fault_pairs = fo.fault_pairs_csv.empty() ? stem + "_fault_" : fo.fault_pairs_csv;
  const std::string scenario_csv = fo.scenario_csv.empty() ? stem + "_scenario.csv" : fo.scenario_csv;
  auto t0 = Clock::now();

  // 1. Inputs (rank 0): the model, its faults, the pressure history.
  std::unique_ptr<Root> root;
  Settings set;
  double until = INFINITY;
  mech::collective(comm, [&] {
    if (rank != 0) return;
    root = std::make_unique<Root>();
    Root& R = *root;
    R.mesh = mesh;
    R.cs = cs;
    if (!o.restart.empty())
      throw InputError("--restart", "a faulted run cannot resume from a state file (the fault state is not saved): run it "
                                    "from the start");
    if (!o.until.empty()) {
      const auto t = parse_iso_date(o.until);
      if (!t) throw InputError("--until", fmt::format("'{}' is not an ISO 8601 date", o.until));
      until = static_cast<double>(*t);
    }
    log(1, fmt::format("mesh: {} nodes, {} tetrahedra, {} interface elements", mesh->num_nodes(),
                       mesh->count(ElementType::Tetrahedron), mesh->count(ElementType::Prism)));
    R.model = mech::build_model(*mesh, *cs, true);
    R.fm = build_fault_model(*mesh, *cs, R.model, geostatic_fault_state(R.model.initial));
    for (const auto& f : R.fm.faults) {
      // The initial state against the Mohr-Coulomb limit (the thesis' figures 4.41-4.42).
      double chi0 = 0;
      std::size_t over = 0;
      for (const auto& p : R.fm.pairs) {
        if (&R.fm.faults[p.fault] != &f || !p.frictional()) continue;
        const double c = safety_factor(std::hypot(p.lambda0[0], p.lambda0[1]), p.lambda0[2] + p.p0, f.cohesion, f.mu,
                                       p.lambda0[2] + p.p0 > 0 ? PairState::Open : PairState::Stick);
        chi0 = std::max(chi0, c);
        over += c > 1;
      }
      log(0, fmt::format("fault {}: {} interface elements, {:.4g} km2, {} node pairs, {} tip nodes; cohesion {:g} MPa, friction "
                         "{:g} deg; initial chi up to {:.3f}", f.name, f.elements, f.area * 1e-6, f.pairs, f.tip_nodes,
                         f.cohesion * 1e-6, f.friction_deg, chi0));
      if (over)
        log(-1, fmt::format("fault {}: the geostatic stress exceeds the Mohr-Coulomb strength at {} node pairs (chi up to "
                            "{:.3f}): they slip in the first step", f.name, over, chi0));
    }
    if (R.fm.redundant_pairs)
      log(1, fmt::format("{} node pairs close cycles at fault junctions (regularised)", R.fm.redundant_pairs));
    if (R.fm.boundary_pairs)
      log(1, fmt::format("{} node pairs lie on prescribed boundaries (constrained in their free directions only); {} of them "
                         "lack a free normal or shear and are left out of the statistics",
                         R.fm.boundary_pairs, R.fm.inactive_pairs));
    R.history = std::make_unique<mech::PressureHistory>(o.pressure, *mesh, R.model);
    log(1, fmt::format("pressure: {} file(s), {} dates, {} of {} elements under a pressure change", o.pressure.size(),
                       R.history->steps().size(), R.history->forced_cells(), R.model.tets.size()));
    for (const auto& d : cs->output_dates) R.history->add_step(d, cs->path + ": [output] dates");
    if (!cs->scenario_reference_date.empty()) {
      R.history->add_step(cs->scenario_reference_date, cs->path + ": [scenario] reference_date");
      set.ref_time = static_cast<double>(*parse_iso_date(cs->scenario_reference_date));
    } else {
      set.ref_time = R.history->steps().front().time;
    }
    R.fields.insert(cs->output_fields.begin(), cs->output_fields.end());
    if (R.fields.empty()) R.fields = {"displacement", "strain", "stress", "stress_change", "cm", "state"};
    set.linear = static_cast<int>(mech::parse_linear_solver(o.solver.empty() ? cs->linear_solver : o.solver));
    set.partition = static_cast<int>(mech::parse_partition_method(o.partition));
    set.fault_solver = static_cast<int>(parse_saddle_solver(fo.fault_solver.empty() ? cs->fault_solver : fo.fault_solver));
    set.tolerance = cs->newton_tolerance;
    set.max_newton = cs->max_newton_iterations;
    set.max_substeps = cs->max_substeps;
    set.reuse = cs->reuse_preconditioner ? 1 : 0;
    set.scale = fo.scale ? *fo.scale : cs->scenario_scale;
    if (!(set.scale >= 0)) throw InputError("--scale", "the pressure scale must not be negative");
    set.search = fo.find_safe_scale ? 1 : 0;
    set.max_scale = cs->scenario_max_scale;
    set.scale_tolerance = cs->scenario_tolerance;
    if (R.model.top_nodes.empty()) log(-1, "the mesh has no bnd:top group: no top-surface table is written");
  });
  MPI_Bcast(&set, sizeof(Settings), MPI_BYTE, 0, comm);
  MPI_Bcast(&until, 1, MPI_DOUBLE, 0, comm);
  sum.seconds_read = since(t0);

  // 2. Steps.
  std::vector<std::string> dates;
  std::vector<double> times;
  std::vector<char> is_output;
  if (rank == 0) {
    const std::set<std::string> outs(cs->output_dates.begin(), cs->output_dates.end());
    std::set<double> out_times;
    for (const auto& d : outs) out_times.insert(static_cast<double>(*parse_iso_date(d)));
    for (const auto& s : root->history->steps()) {
      if (s.time > until) continue;
      dates.push_back(s.date);
      times.push_back(s.time);
      is_output.push_back(outs.empty() || out_times.count(s.time));
    }
  }
  dates = broadcast_strings(comm, dates);
  std::uint64_t nsteps = dates.size();
  MPI_Bcast(&nsteps, 1, MPI_UINT64_T, 0, comm);
  times.resize(nsteps);
  is_output.resize(nsteps);
  if (nsteps) {
    MPI_Bcast(times.data(), static_cast<int>(nsteps), MPI_DOUBLE, 0, comm);
    MPI_Bcast(is_output.data(), static_cast<int>(nsteps), MPI_CHAR, 0, comm);
  }

  // 3. The distributed solver with the fault contact.
  t0 = Clock::now();
  mech::SolverOptions sopt;
  sopt.linear = static_cast<mech::LinearSolver>(set.linear);
  sopt.partition = static_cast<mech::PartitionMethod>(set.partition);
  sopt.tolerance = set.tolerance;
  sopt.max_newton = set.max_newton;
  sopt.max_substeps = set.max_substeps;
  sopt.reuse_preconditioner = set.reuse != 0;
  mech::MechanicsSolver solver(comm, rank == 0 ? &root->model : nullptr, sopt);
  ContactOptions copt;
  copt.solver = static_cast<SaddleSolver>(set.fault_solver);
  copt.amg = "gamg";  // on the displacement block whatever the continuous solver: the faster here (docs/fault-mechanics.md)
  copt.reuse_preconditioner = sopt.reuse_preconditioner;
  FaultContact contact(comm, rank == 0 ? &root->fm : nullptr, copt);
  solver.set_coupling(contact);
  log(1, fmt::format("{} nodes ({} on rank 0), {} cells; faults: {}", solver.global_nodes(), solver.local_nodes(),
                     solver.global_cells(), contact.description()));
  const std::vector<std::string> comments{"ugs-solve fault statistics per fault and date (node pairs on free degrees of freedom)",
                                          o.command_line};
  mech::collective(comm, [&] {
    if (rank != 0) return;
    Root& R = *root;
    FieldSeriesOptions vol;
    vol.cell_types = {ElementType::Tetrahedron};
    R.results = std::make_unique<FieldSeriesWriter>(o.output, *R.mesh, vol);
    if (top_path != "none" && !R.model.top_nodes.empty()) {
      R.top_mesh = make_top_mesh(*R.mesh, R.model);
      R.top = std::make_unique<FieldSeriesWriter>(top_path, R.top_mesh);
    }
    if (!o.top_csv.empty() && !R.model.top_nodes.empty()) {
      const std::vector<std::string> c{"ugs-solve top-surface displacement (bnd:top nodes), one row per node and date", o.command_line};
      R.top_csv = std::make_unique<CsvWriter>(o.top_csv, std::vector<std::string>{"date", "node", "x_m", "y_m", "ux_mm", "uy_mm", "uz_mm"},
                                              c);
    }
    R.faults = std::make_unique<FaultOutput>(fault_path == "none" ? "" : fault_path, fault_csv == "none" ? "" : fault_csv, R.fm,
                                             comments, fault_pairs == "none" ? "" : fault_pairs);
  });
  sum.seconds_setup = since(t0);

  // Pressure changes of step i at scale s (rank 0): per element and per node pair.
  auto pressures = [&](std::size_t i, double s, std::vector<double>& cell, std::vector<double>& pair) {
    if (rank != 0) return;
    Root& R = *root;
    cell = R.history->cell_dp(times[i]);
    std::vector<double> node = R.history->node_dp(times[i]);
    if (times[i] > set.ref_time && s != 1.0) {
      scale_about(cell, R.ref_cell, s);
      scale_about(node, R.ref_node, s);
    }
    pair.resize(R.fm.pairs.size());
    for (std::size_t q = 0; q < pair.size(); ++q) pair[q] = 0.5 * (node[R.fm.pairs[q].side1] + node[R.fm.pairs[q].side2]);
  };
  if (rank == 0) {
    Root& R = *root;
    R.ref_cell = R.history->cell_dp(set.ref_time);
    R.ref_node = R.history->node_dp(set.ref_time);
  }

  // 4. March over the steps (the base run, at the case's scale), writing everything.
  Watch base;
  bool critical_before = false;
  bool have_snapshot = false;
  FaultContact::Snapshot contact_snapshot;
  std::size_t first_after = nsteps;
  for (std::size_t i = 0; i < nsteps; ++i)
    if (times[i] > set.ref_time) {
      first_after = i;
      break;
    }
  if (set.search && first_after == 0) {
    // The reference is the state before the first step.
    mech::SavedState st = solver.gather_state();
    if (rank == 0) root->snapshot = std::move(st);
    contact_snapshot = contact.save();
    have_snapshot = true;
  }
  for (std::size_t i = 0; i < nsteps; ++i) {
    const std::string label = fmt::format("step {}/{} ({})", i + 1, nsteps, dates[i]);
    std::vector<double> dp, dpf;
    mech::collective(comm, [&] { pressures(i, set.scale, dp, dpf); });
    contact.set_pressure_change(dpf);
    const auto before = contact.stats();
    const mech::StepReport rep = solver.advance(dp, label);
    sum.seconds_solve += rep.seconds;
    sum.newton_iterations += rep.newton_iterations;
    sum.linear_iterations += rep.linear_iterations;
    sum.substeps += rep.substeps;
    if (!rep.converged) throw ComputeError(rep.failure);
    const auto to = Clock::now();
    const std::vector<double> u = solver.gather_displacement();
    mech::CellResults cells;
    if (is_output[i]) cells = solver.gather_cells();
    const PairResults pr = contact.gather();
    std::string fault_note;
    mech::collective(comm, [&] {
      if (rank != 0) return;
      Root& R = *root;
      const FaultFields ff = derive_fault_fields(R.fm, pr);
      if (times[i] > set.ref_time) base.see(R.fm, ff, dates[i]);
      else {
        Watch w;
        w.see(R.fm, ff, dates[i]);
        critical_before = critical_before || w.critical;
      }
      const auto stats = fault_date_stats(R.fm, ff);
      double mc = 0;
      std::size_t ns = 0, no = 0;
      std::string worst;
      for (std::size_t k = 0; k < stats.size(); ++k) {
        if (stats[k].max_chi >= mc) mc = stats[k].max_chi, worst = R.fm.faults[k].name;
        ns += stats[k].slipping;
        no += stats[k].open;
      }
      fault_note = fmt::format("max chi {:.3f} ({}), {} node pairs slipping, {} open", mc, worst, ns, no);
      R.faults->add(dates[i], times[i], ff, is_output[i]);
      mech::write_top_surface(R.top.get(), R.top_csv.get(), *R.mesh, R.model, dates[i], times[i], u);
      if (is_output[i]) mech::write_volume_fields(*R.results, R.fields, *R.history, dates[i], times[i], u, cells);
    });
    const auto& after = contact.stats();
    log(1, fmt::format("{}: {} Newton iteration{}, {} linear iterations, {} sub-step{}, {} contact state changes, {:.2f} s; {}",
                       label, rep.newton_iterations, rep.newton_iterations == 1 ? "" : "s", rep.linear_iterations,
                       rep.substeps, rep.substeps == 1 ? "" : "s", after.state_changes - before.state_changes, rep.seconds,
                       fault_note));
    if (!rep.substep_reason.empty())
      log(1, fmt::format("{}: split into {} sub-steps: {}", label, rep.substeps, rep.substep_reason));
    if (set.search && !have_snapshot && i + 1 == first_after) {
      mech::SavedState st = solver.gather_state();
      if (rank == 0) root->snapshot = std::move(st);
      contact_snapshot = contact.save();
      have_snapshot = true;
    }
    sum.seconds_output += since(to);
    ++sum.steps;
    if (rank == 0 && o.progress) o.progress(i + 1, nsteps);
  }
  int cb = critical_before ? 1 : 0;
  MPI_Bcast(&cb, 1, MPI_INT, 0, comm);
  critical_before = cb != 0;

  // 5. The safe-scale search: reruns from the reference state.
  SafeScale safe;
  if (set.search) {
    safe.searched = true;
    if (!have_snapshot || first_after >= nsteps)
      throw InputError(cs ? cs->path : "case", "[scenario] reference_date: no step after it to scale");
    std::unique_ptr<CsvWriter> trials;
    mech::collective(comm, [&] {
      if (rank != 0) return;
      const std::vector<std::string> c{"ugs-solve safe-scale search: dp_s(t) = dp(t_ref) + scale (dp(t) - dp(t_ref)) after the "
                                       "reference date; critical = some fault patch reaches chi = 1",
                                       o.command_line};
      trials = std::make_unique<CsvWriter>(scenario_csv,
                                           std::vector<std::string>{"scale", "max_chi", "critical", "fault", "date", "x_m", "y_m",
                                                                    "z_m", "dp_max_MPa", "dp_min_MPa", "note"},
                                           c);
    });
    auto trial = [&](double s) {
      solver.restore_state(rank == 0 ? root->snapshot : mech::SavedState{});
      contact.restore(contact_snapshot);
      Watch w;
      std::string note;
      for (std::size_t i = first_after; i < nsteps; ++i) {
        std::vector<double> dp, dpf;
        mech::collective(comm, [&] { pressures(i, s, dp, dpf); });
        if (rank == 0)
          for (double v : dp) w.dp_max = std::max(w.dp_max, v), w.dp_min = std::min(w.dp_min, v);
        contact.set_pressure_change(dpf);
        const mech::StepReport rep = solver.advance(dp, fmt::format("scale {:.4g}, {}", s, dates[i]));
        sum.newton_iterations += rep.newton_iterations;
        sum.linear_iterations += rep.linear_iterations;
        if (!rep.converged) {
          // Newton fails only where faults slip widely: count it as critical.
          note = "Newton failed: " + rep.failure;
          if (rank == 0 && !w.critical) w.critical = true, w.date = dates[i], w.max_chi = std::max(w.max_chi, 1.0);
          break;
        }
        const PairResults pr = contact.gather();
        if (rank == 0) w.see(root->fm, derive_fault_fields(root->fm, pr), dates[i]);
      }
      int c = w.critical ? 1 : 0;
      MPI_Bcast(&c, 1, MPI_INT, 0, comm);
      w.critical = c != 0;
      mech::collective(comm, [&] {
        if (rank != 0) return;
        trials->number(s, 6).number(w.max_chi, 6).integer(w.critical ? 1 : 0).text(w.fault).text(w.date);
        trials->number(w.at[0], 2).number(w.at[1], 2).number(w.at[2], 2);
        trials->number(w.dp_max * 1e-6, 4).number(w.dp_min * 1e-6, 4).text(note).end_row();
      });
      log(0, fmt::format("scale {:.4g}: max chi {:.4f}{}", s, w.max_chi,
                         w.critical ? fmt::format(" — critical: fault {} on {}", w.fault, w.date) : ""));
      return w;
    };
    if (critical_before) {
      safe.critical_before = true;
      log(-1, "a fault patch reaches chi = 1 before or at the reference date: no scale of the later swing is safe");
    } else {
      double lo = 0, hi = -1;
      Watch lo_w, hi_w;
      lo_w.dp_max = lo_w.dp_min = 0;
      for (double s = 1; ; s = std::min(2 * s, set.max_scale)) {
        const Watch w = trial(s);
        if (w.critical) {
          hi = s, hi_w = w;
          break;
        }
        lo = s, lo_w = w;
        if (s >= set.max_scale) break;
      }
      if (hi > 0) {
        while (hi - lo > set.scale_tolerance * hi) {
          const double mid = 0.5 * (lo + hi);
          const Watch w = trial(mid);
          if (w.critical) hi = mid, hi_w = w;
          else lo = mid, lo_w = w;
        }
        safe.found = true;
        safe.critical = hi;
        safe.fault = hi_w.fault;
        safe.date = hi_w.date;
        safe.at = hi_w.at;
      }
      safe.safe = lo;
      safe.peak_dp_max = lo_w.dp_max;
      safe.peak_dp_min = lo_w.dp_min;
      if (safe.found)
        log(0, fmt::format("maximum safe scale {:.4g} (critical at {:.4g}: fault {} first reaches chi = 1 on {} at ({:.0f}, "
                           "{:.0f}, {:.0f})); the pressure change then peaks at {:+.3f} MPa / {:+.3f} MPa",
                           safe.safe, safe.critical, safe.fault, safe.date, safe.at[0], safe.at[1], safe.at[2],
                           safe.peak_dp_max * 1e-6, safe.peak_dp_min * 1e-6));
      else
        log(0, fmt::format("no fault patch reaches chi = 1 up to scale {:.4g} (max_scale)", safe.safe));
    }
    mech::collective(comm, [&] {
      if (rank == 0) trials->commit();
    });
  }
  if (safe_out) *safe_out = safe;

  // 6. Commit: a failed run leaves no results behind.
  mech::collective(comm, [&] {
    if (rank != 0) return;
    Root& R = *root;
    for (const auto& n : R.history->notes()) log(-1, n);
    R.results->commit();
    if (R.top) R.top->commit();
    if (R.top_csv) R.top_csv->commit();
    R.faults->commit();
  });
  const ContactStats& cst = contact.stats();
  log(1, fmt::format("faults: {} saddle-point solves, {} linear iterations, {} preconditioner setups, {:.2f} s in the contact "
                     "solver", cst.solves, cst.linear_iterations, cst.preconditioner_setups, cst.seconds));
  return sum;
}

}  // namespace ugs::contact
