#include "ugs/calibration/evaluator.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <thread>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/runner/content_hash.hpp"
#include "ugs/runner/solver_runs.hpp"

namespace ugs::calibration {

// The PS-side types (samples, misfit) and the runner (case templates, solver runs).
using namespace ugs::insar;
using namespace ugs::runner;

namespace fs = std::filesystem;

// ---- SimulatedSeries ----------------------------------------------------------------------------

void SimulatedSeries::write_csv(const std::string& path) const {
  CsvWriter w(path, {"pid", "date", "east_m", "north_m", "up_m"});
  for (std::size_t p = 0; p < ids.size(); ++p)
    for (std::size_t t = 0; t < times.size(); ++t) {
      const double* v = enu.data() + (p * times.size() + t) * 3;
      w.text(ids[p]).date(times[t]).number(v[0]).number(v[1]).number(v[2]).end_row();
    }
  w.commit();
}

SimulatedSeries SimulatedSeries::read_csv(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  const auto cp = t.column("pid"), cd = t.column("date"), ce = t.column("east_m"), cn = t.column("north_m"),
             cu = t.column("up_m");
  SimulatedSeries s;
  std::unordered_map<std::string, std::size_t> seen;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::string id(t.text(r, cp));
    if (seen.emplace(id, s.ids.size()).second) s.ids.push_back(id);
    if (s.ids.size() == 1) s.times.push_back(t.date(r, cd));
  }
  if (s.ids.empty() || t.rows() != s.ids.size() * s.times.size())
    throw InputError(path, "not a complete series table (every point at every date)");
  s.enu.resize(t.rows() * 3);
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::size_t p = seen[std::string(t.text(r, cp))];
    const std::size_t k = r % s.times.size();
    if (r / s.times.size() != p || t.date(r, cd) != s.times[k]) throw InputError(t.where(r), "series rows out of order");
    double* v = s.enu.data() + (p * s.times.size() + k) * 3;
    v[0] = t.number(r, ce);
    v[1] = t.number(r, cn);
    v[2] = t.number(r, cu);
  }
  return s;
}

bool SimulatedSeries::has(const std::string& id) const { return std::find(ids.begin(), ids.end(), id) != ids.end(); }

Samples SimulatedSeries::at_dates(const std::vector<LocatedPoint>& points, const std::vector<std::int64_t>& dates) const {
  Samples s;
  s.points = points;
  s.dates = dates;
  s.enu.assign(points.size() * dates.size() * 3, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto it = std::find(ids.begin(), ids.end(), points[p].point.id);
    if (it == ids.end()) continue;
    const std::size_t q = static_cast<std::size_t>(it - ids.begin());
    for (std::size_t d = 0; d < dates.size(); ++d) {
      const auto b = bracket_time(times, dates[d]);
      if (!b) continue;
      const double* a = enu.data() + (q * times.size() + b->i0) * 3;
      const double* c = enu.data() + (q * times.size() + b->i1) * 3;
      double* out = s.enu.data() + (p * dates.size() + d) * 3;
      for (int j = 0; j < 3; ++j) out[j] = (1 - b->w) * a[j] + b->w * c[j];
    }
  }
  return s;
}

// ---- Evaluator ------------------------------------------------------------------------------------

namespace {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

SolverRunSetup runs_setup(const EvaluatorSetup& s) {
  if (!s.case_template) throw std::invalid_argument("Evaluator: no case");
  SolverRunSetup r;
  r.case_template = s.case_template;
  r.command = s.solver_command;
  r.mesh_path = s.mesh_path;
  r.cache_dir = s.cache_dir;
  r.extra = s.setup_extra;
  r.key_label = "ugs-calibrate cache key 2";
  r.entry_prefix = "eval-";
  r.keep_results = s.keep_results;
  return r;
}

}  // namespace

Evaluator::Evaluator(EvaluatorSetup setup) : setup_(std::move(setup)), runs_(runs_setup(setup_)) {
  if (setup_.jobs < 1) setup_.jobs = 1;
  setup_.cache_dir = runs_.cache_dir();
  // Rows of earlier runs stay in the index.
  const fs::path index = fs::path(setup_.cache_dir) / "index.csv";
  if (fs::exists(index)) {
    try {
      const CsvTable t = CsvTable::read(index.string());
      const auto ce = t.column("entry"), cp = t.column("parameters"), cr = t.column("rms_mm");
      for (std::size_t r = 0; r < t.rows(); ++r) {
        const std::string e(t.text(r, ce));
        index_rows_[e] = fmt::format("{},{},{}", csv_quote(e), csv_quote(std::string(t.text(r, cp))),
                                     csv_quote(std::string(t.text(r, cr))));
      }
    } catch (const InputError&) {
      // A damaged index is rebuilt from this run's entries.
    }
  }
}

ParameterValues Evaluator::values_of(const std::vector<double>& x) const {
  ParameterValues v;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (const auto& p : setup_.params[i].paths) v.emplace_back(p, x[i]);
  return v;
}

std::string Evaluator::key(const std::vector<double>& x) const { return runs_.key(values_of(x)); }

std::string Evaluator::entry_name(const std::vector<double>& x) const { return runs_.entry_name(values_of(x)); }

const SimulatedSeries& Evaluator::series_of(const Evaluation& e) {
  std::lock_guard lock(mutex_);
  auto it = series_.find(e.entry);
  if (it == series_.end())
    it = series_.emplace(e.entry, SimulatedSeries::read_csv((fs::path(setup_.cache_dir) / e.entry / "series.csv").string())).first;
  return it->second;
}

Evaluation Evaluator::run_one(const std::vector<double>& x) {
  Evaluation ev;
  ev.x = x;
  const ParameterValues values = values_of(x);
  ev.entry = runs_.entry_name(values);
  const fs::path entry = runs_.entry_path(ev.entry);
  // A cache hit: same key, and every point we need.
  if (runs_.complete(values) && fs::exists(entry / "series.csv")) {
    try {
      SimulatedSeries s = SimulatedSeries::read_csv((entry / "series.csv").string());
      bool complete = true;
      for (const auto& id : setup_.needed_ids) complete = complete && s.has(id);
      if (complete) {
        ev.cached = true;
        ev.misfit = setup_.misfit(s);
        std::lock_guard lock(mutex_);
        series_[ev.entry] = std::move(s);
        return ev;
      }
    } catch (const InputError&) {
      // damaged entry: computed again below
    }
  }
  std::string params;
  for (std::size_t i = 0; i < x.size(); ++i) params += (i ? ", " : "") + setup_.params[i].name + " = " + toml_float(x[i]);
  SimulatedSeries s;
  ev.seconds = runs_.run(values, "evaluation at " + params, [&](const std::string& folder, const std::string& h5) {
    {
      static std::mutex hdf5_mutex;  // HDF5 may be built without thread safety: one reader at a time
      std::lock_guard hdf5_lock(hdf5_mutex);
      s = setup_.sample(h5);
    }
    s.write_csv((fs::path(folder) / "series.csv").string());
  });
  ev.misfit = setup_.misfit(s);
  std::lock_guard lock(mutex_);
  series_[ev.entry] = std::move(s);
  return ev;
}

std::vector<Evaluation> Evaluator::evaluate(const std::vector<std::vector<double>>& xs, const std::string& phase) {
  std::vector<Evaluation> out(xs.size());
  // Points already evaluated in this run are answered from the history.
  std::vector<std::size_t> to_run;                          // indices into xs of the points to run
  std::unordered_map<std::string, std::size_t> first_of;  // entry -> index into xs of its first occurrence
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const std::string name = entry_name(xs[i]);
    const auto h = std::find_if(history_.begin(), history_.end(), [&](const Evaluation& e) { return e.entry == name; });
    if (h != history_.end()) {
      out[i] = *h;
      out[i].cached = true;
      out[i].seconds = 0;
    } else if (first_of.emplace(name, i).second) {
      to_run.push_back(i);
    }
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex fail_mutex;
  auto worker = [&] {
    for (;;) {
      const std::size_t j = next++;
      if (j >= to_run.size()) return;
      {
        std::lock_guard lock(fail_mutex);
        if (failure) return;
      }
      try {
        out[to_run[j]] = run_one(xs[to_run[j]]);
      } catch (...) {
        std::lock_guard lock(fail_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  const std::size_t nthreads = std::min<std::size_t>(static_cast<std::size_t>(setup_.jobs), to_run.size());
  std::vector<std::thread> threads;
  for (std::size_t t = 1; t < nthreads; ++t) threads.emplace_back(worker);
  if (nthreads > 0) worker();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  // Duplicates within the batch, history, index, in request order.
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (out[i].entry.empty()) {
      out[i] = out[first_of.at(entry_name(xs[i]))];
      out[i].cached = true;
      out[i].seconds = 0;
    }
    out[i].phase = phase;
    out[i].index = history_.size() + 1;
    history_.push_back(out[i]);
    std::string params;
    for (const auto& [p, v] : values_of(xs[i])) params += (params.empty() ? "" : ";") + p + "=" + toml_float(v);
    // The misfit of this run (it depends on the measured series, which are not in the key).
    index_rows_[out[i].entry] = fmt::format("{},{},{:.6f}", out[i].entry, csv_quote(params), out[i].misfit.rms_mm);
    if (on_evaluation) on_evaluation(out[i]);
  }
  write_index();
  return out;
}

void Evaluator::write_index() {
  OutputFile f((fs::path(setup_.cache_dir) / "index.csv").string());
  f.write("# ugs-calibrate cache: one folder per evaluation (case.toml, series.csv, entry.json, inputs.txt, solver.log, "
          "timing.txt); rms_mm of the latest run\n");
  f.write("entry,parameters,rms_mm\n");
  for (const auto& [entry, row] : index_rows_) f.write(row + "\n");
  f.commit();
}

}  // namespace ugs::calibration
