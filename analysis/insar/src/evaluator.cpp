#include "ugs/insar/evaluator.hpp"

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
#include "ugs/insar/content_hash.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/subprocess.hpp"

namespace ugs::insar {

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

// The program `name` as the shell would find it in PATH ("" if not found).
std::string find_in_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path || name.empty()) return "";
  std::string_view rest = path;
  while (true) {
    const auto colon = rest.find(':');
    const std::string dir(rest.substr(0, colon));
    std::error_code ec;
    const fs::path p = fs::path(dir.empty() ? "." : dir) / name;
    if (fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return fs::absolute(p).lexically_normal().string();
    if (colon == std::string_view::npos) return "";
    rest.remove_prefix(colon + 1);
  }
}

std::string substitute(const std::string& tmpl, const std::map<std::string, std::string>& values) {
  std::string out;
  for (std::size_t i = 0; i < tmpl.size();) {
    if (tmpl[i] == '{' && (i == 0 || tmpl[i - 1] != '$')) {
      const auto close = tmpl.find('}', i);
      if (close != std::string::npos) {
        const auto it = values.find(tmpl.substr(i + 1, close - i - 1));
        if (it != values.end()) {
          out += it->second;
          i = close + 1;
          continue;
        }
      }
    }
    out += tmpl[i++];
  }
  return out;
}

std::string json_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    if (c == '\n') {
      q += "\\n";
      continue;
    }
    q += c;
  }
  return q + "\"";
}

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void write_text(const fs::path& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
  if (!f) throw ComputeError(fmt::format("cannot write {}", p.string()));
}

}  // namespace

std::vector<std::string> files_named_in_command(const std::string& cmd) {
  // Words as /bin/sh splits them (quotes removed, no expansion); operators end a simple command.
  struct Word {
    std::string text;
    bool command_position;
  };
  std::vector<Word> words;
  std::string cur;
  bool have = false, at_command = true;
  auto flush = [&] {
    if (!have) return;
    words.push_back({cur, at_command});
    // VAR=value before the program keeps the command position.
    const auto eq = cur.find('=');
    const bool assignment = at_command && eq != std::string::npos && eq > 0 &&
                            std::all_of(cur.begin(), cur.begin() + static_cast<std::ptrdiff_t>(eq),
                                        [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!assignment) at_command = false;
    cur.clear();
    have = false;
  };
  for (std::size_t i = 0; i < cmd.size(); ++i) {
    const char c = cmd[i];
    if (c == '\'' || c == '"') {
      const auto close = cmd.find(c, i + 1);
      const std::size_t end = close == std::string::npos ? cmd.size() : close;
      cur += cmd.substr(i + 1, end - i - 1);
      have = true;
      i = end;
    } else if (c == '\\' && i + 1 < cmd.size()) {
      cur += cmd[++i];
      have = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      flush();
    } else if (c == ';' || c == '&' || c == '|' || c == '(' || c == ')' || c == '\n') {
      flush();
      at_command = true;
    } else if (c == '<' || c == '>') {
      flush();
    } else {
      cur += c;
      have = true;
    }
  }
  flush();
  std::vector<std::string> files;
  auto consider = [&](const std::string& w) {
    if (w.empty() || w.find('{') != std::string::npos || w.find('$') != std::string::npos) return;
    std::error_code ec;
    if (fs::is_regular_file(w, ec)) files.push_back(fs::absolute(w).lexically_normal().string());
  };
  for (const auto& w : words) {
    if (w.command_position && w.text.find('/') == std::string::npos && w.text.find('=') == std::string::npos) {
      const std::string p = find_in_path(w.text);
      if (!p.empty()) files.push_back(p);
      continue;
    }
    consider(w.text);
    const auto eq = w.text.find('=');
    if (eq != std::string::npos) consider(w.text.substr(eq + 1));
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

void check_command_template(const std::string& cmd, bool have_mesh) {
  if (cmd.find("{case}") == std::string::npos || cmd.find("{out}") == std::string::npos)
    throw InputError("--solver-command", "the command must contain {case} (the modified case file) and {out} (the results "
                                         "file it must write)");
  static const std::regex placeholder(R"(\{([A-Za-z_]+)\})");
  for (auto it = std::sregex_iterator(cmd.begin(), cmd.end(), placeholder); it != std::sregex_iterator(); ++it) {
    if (it->position() > 0 && cmd[static_cast<std::size_t>(it->position()) - 1] == '$') continue;  // ${VAR} is the shell's
    const std::string name = (*it)[1];
    if (name != "case" && name != "out" && name != "mesh" && name != "dir")
      throw InputError("--solver-command", fmt::format("unknown placeholder {{{}}} (known: {{case}} {{out}} {{mesh}} {{dir}})", name));
  }
  if (cmd.find("{mesh}") != std::string::npos && !have_mesh)
    throw InputError("--solver-command", "uses {mesh} but no --mesh was given");
}

Evaluator::Evaluator(EvaluatorSetup setup) : setup_(std::move(setup)) {
  if (!setup_.case_template) throw std::invalid_argument("Evaluator: no case");
  const std::string& cmd = setup_.solver_command;
  check_command_template(cmd, !setup_.mesh_path.empty());
  if (setup_.jobs < 1) setup_.jobs = 1;
  // The key's inputs, by content: the key text holds the hashes in a fixed order, inputs.txt also
  // the names (a moved or renamed file with the same bytes keeps its cache entries).
  std::string key_text = "ugs-calibrate cache key 2\n";
  auto add = [&](const std::string& role, const std::string& hash, const std::string& name) {
    key_text += role + " " + hash + "\n";
    inputs_ += role + " " + hash + (name.empty() ? "" : " " + name) + "\n";
  };
  add("case-text", sha256_hex(setup_.case_template->text()), setup_.case_template->path());
  for (const auto& f : setup_.case_template->referenced_files()) add("case-file", sha256_file_hex(f), f);
  add("command-template", sha256_hex(cmd), cmd);
  for (const auto& f : files_named_in_command(cmd)) add("command-file", sha256_file_hex(f), f);
  if (!setup_.mesh_path.empty()) add("mesh", sha256_file_hex(setup_.mesh_path), setup_.mesh_path);
  add("extra", sha256_hex(setup_.setup_extra), "");
  setup_hash_ = sha256_hex(key_text);
  std::error_code ec;
  fs::create_directories(setup_.cache_dir, ec);
  if (ec) throw InputError(setup_.cache_dir, "cannot create the cache folder: " + ec.message());
  // The solver runs inside its evaluation folder: {dir}, {out}, {case} and {mesh} must not be
  // relative to ours.
  setup_.cache_dir = fs::absolute(setup_.cache_dir).lexically_normal().string();
  if (!setup_.mesh_path.empty()) setup_.mesh_path = fs::absolute(setup_.mesh_path).lexically_normal().string();
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

std::string Evaluator::key(const std::vector<double>& x) const {
  std::string k = setup_hash_;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (const auto& p : setup_.params[i].paths) k += "|" + p + "=" + toml_float(x[i]);
  return k;
}

std::string Evaluator::entry_name(const std::vector<double>& x) const { return "eval-" + sha256_hex(key(x)).substr(0, 20); }

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
  ev.entry = entry_name(x);
  const std::string k = key(x);
  const fs::path entry = fs::path(setup_.cache_dir) / ev.entry;
  // A cache hit: same key, and every point we need.
  if (fs::exists(entry / "key.txt") && fs::exists(entry / "series.csv") && read_text(entry / "key.txt") == k) {
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
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = fs::path(setup_.cache_dir) / fmt::format(".tmp-{}-{}-{}", ev.entry, ::getpid(), counter++);
  const fs::path failed = fs::path(setup_.cache_dir) / ("failed-" + ev.entry);
  // Whatever happens below, no temporary folder stays: it becomes the entry, or failed-<entry>
  // for a failed solver run (the error names it), or it is removed.
  struct TmpGuard {
    fs::path path;
    ~TmpGuard() {
      std::error_code ec;
      if (!path.empty()) fs::remove_all(path, ec);
    }
  } guard{tmp};
  auto keep_as_failed = [&] {
    std::error_code ec;
    fs::remove_all(failed, ec);
    fs::rename(tmp, failed, ec);
    return ec ? tmp.string() + " (removed)" : failed.string();
  };
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  std::vector<std::pair<std::string, double>> values;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (const auto& p : setup_.params[i].paths) values.emplace_back(p, x[i]);
  write_text(tmp / "case.toml", setup_.case_template->render(values));
  write_text(tmp / "inputs.txt", inputs_);
  const fs::path out = tmp / "result.h5";
  auto command_in = [&](const fs::path& dir) {
    return substitute(setup_.solver_command, {{"case", shell_quote((dir / "case.toml").string())},
                                              {"out", shell_quote((dir / "result.h5").string())},
                                              {"mesh", shell_quote(setup_.mesh_path)},
                                              {"dir", shell_quote(dir.string())}});
  };
  const std::string cmd = command_in(tmp);
  // The record names the entry's own folder, not the temporary one (whose name holds the process id):
  // the same evaluation writes the same bytes.
  write_text(tmp / "command.sh", command_in(entry) + "\n");
  const auto r = run_shell(cmd, tmp.string(), (tmp / "solver.log").string());
  std::string params;
  for (std::size_t i = 0; i < x.size(); ++i) params += (i ? ", " : "") + setup_.params[i].name + " = " + toml_float(x[i]);
  if (r.exit_code != 0) {
    const std::string why = last_line((tmp / "solver.log").string());
    throw ComputeError(fmt::format("evaluation at {}: the solver exited with code {}: {} (log and case kept in {})", params,
                                   r.exit_code, why, keep_as_failed()));
  }
  if (!fs::exists(out))
    throw ComputeError(fmt::format("evaluation at {}: the solver wrote no result.h5 (the command must write {{out}}; log in {})",
                                   params, keep_as_failed()));
  SimulatedSeries s;
  try {
    static std::mutex hdf5_mutex;  // HDF5 may be built without thread safety: one reader at a time
    std::lock_guard hdf5_lock(hdf5_mutex);
    s = setup_.sample(out.string());
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw ComputeError(fmt::format("evaluation at {}: cannot sample the solver's results: {} (kept in {})", params, what,
                                   keep_as_failed()));
  }
  s.write_csv((tmp / "series.csv").string());
  // entry.json holds what the series depends on, nothing that changes from run to run: the wall
  // time goes to timing.txt (and stderr).
  std::string json = "{\n  \"key\": " + json_string(k) + ",\n  \"parameters\": {";
  for (std::size_t i = 0; i < values.size(); ++i)
    json += fmt::format("{}\n    {}: {}", i ? "," : "", json_string(values[i].first), toml_float(values[i].second));
  json += fmt::format("\n  }},\n  \"command\": {}\n}}\n", json_string(setup_.solver_command));
  write_text(tmp / "entry.json", json);
  write_text(tmp / "timing.txt", fmt::format("solver_seconds {:.3f}\n", r.seconds));
  if (!setup_.keep_results) {
    fs::remove(out);
    fs::remove(fs::path(out).replace_extension(".xdmf"));
  }
  write_text(tmp / "key.txt", k);  // last: its presence marks a complete entry
  std::error_code ec;
  fs::remove_all(entry, ec);
  fs::rename(tmp, entry, ec);
  if (!ec) {
    guard.path.clear();
    fs::remove_all(failed, ec);  // an earlier failure at these values is history
  }
  // else another process won the race: its entry is as good (the guard removes ours)
  ev.seconds = r.seconds;
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
    for (std::size_t k = 0; k < xs[i].size(); ++k)
      for (const auto& p : setup_.params[k].paths) params += (params.empty() ? "" : ";") + p + "=" + toml_float(xs[i][k]);
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

}  // namespace ugs::insar
