#include "ugs/runner/solver_runs.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/runner/content_hash.hpp"
#include "ugs/runner/subprocess.hpp"
#include "remove_at_exit.hpp"

namespace ugs::runner {

namespace fs = std::filesystem;

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

// An entry's record: its key, its values, the command and, for a derived entry, its source.
std::string entry_json(const std::string& key, const ParameterValues& values, const std::string& command,
                       const std::string& derived_from) {
  std::string json = "{\n  \"key\": " + json_string(key) + ",\n  \"parameters\": {";
  for (std::size_t i = 0; i < values.size(); ++i)
    json += fmt::format("{}\n    {}: {}", i ? "," : "", json_string(values[i].first), toml_float(values[i].second));
  json += fmt::format("\n  }},\n  \"command\": {}", json_string(command));
  if (!derived_from.empty()) json += ",\n  \"derived_from\": " + json_string(derived_from);
  return json + "\n}\n";
}

// Turns the finished folder `tmp` into the entry: key.txt written last (its presence marks a
// complete entry), then the atomic rename; an earlier failure at these values is history. When
// another process won the race its entry is as good, and the guard removes ours.
void install_entry(const fs::path& tmp, const fs::path& entry, const std::string& failed, const std::string& key, RemoveAtExit& guard) {
  write_text_file((tmp / "key.txt").string(), key);
  std::error_code ec;
  fs::remove_all(entry, ec);
  fs::rename(tmp, entry, ec);
  if (ec) return;
  guard.release();
  fs::remove_all(failed, ec);
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

}  // namespace

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

std::string read_text_file(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void write_text_file(const std::string& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
  if (!f) throw ComputeError(fmt::format("cannot write {}", p));
}



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
    throw InputError("solver command", "the command must contain {case} (the modified case file) and {out} (the results "
                                         "file it must write)");
  static const std::regex placeholder(R"(\{([A-Za-z_]+)\})");
  for (auto it = std::sregex_iterator(cmd.begin(), cmd.end(), placeholder); it != std::sregex_iterator(); ++it) {
    if (it->position() > 0 && cmd[static_cast<std::size_t>(it->position()) - 1] == '$') continue;  // ${VAR} is the shell's
    const std::string name = (*it)[1];
    if (name != "case" && name != "out" && name != "mesh" && name != "dir")
      throw InputError("solver command", fmt::format("unknown placeholder {{{}}} (known: {{case}} {{out}} {{mesh}} {{dir}})", name));
  }
  if (cmd.find("{mesh}") != std::string::npos && !have_mesh)
    throw InputError("solver command", "uses {mesh} but no solver mesh was given");
}

SolverRuns::SolverRuns(SolverRunSetup setup) : setup_(std::move(setup)) {
  if (!setup_.case_template) throw std::invalid_argument("SolverRuns: no case");
  const std::string& cmd = setup_.command;
  check_command_template(cmd, !setup_.mesh_path.empty());
  // The key's inputs, by content: the key text holds the hashes in a fixed order, inputs.txt also
  // the names (a moved or renamed file with the same bytes keeps its cache entries).
  std::string key_text = setup_.key_label + "\n";
  auto add = [&](const std::string& role, const std::string& hash, const std::string& name) {
    key_text += role + " " + hash + "\n";
    inputs_ += role + " " + hash + (name.empty() ? "" : " " + name) + "\n";
  };
  add("case-text", sha256_hex(setup_.case_template->text()), setup_.case_template->path());
  for (const auto& f : setup_.case_template->referenced_files()) add("case-file", sha256_file_hex(f), f);
  add("command-template", sha256_hex(cmd), cmd);
  for (const auto& f : files_named_in_command(cmd)) add("command-file", sha256_file_hex(f), f);
  if (!setup_.mesh_path.empty()) add("mesh", sha256_file_hex(setup_.mesh_path), setup_.mesh_path);
  add("extra", sha256_hex(setup_.extra), "");
  setup_hash_ = sha256_hex(key_text);
  std::error_code ec;
  fs::create_directories(setup_.cache_dir, ec);
  if (ec) throw InputError(setup_.cache_dir, "cannot create the cache folder: " + ec.message());
  // The solver runs inside its own folder: {dir}, {out}, {case} and {mesh} must not be relative to ours.
  setup_.cache_dir = fs::absolute(setup_.cache_dir).lexically_normal().string();
  if (!setup_.mesh_path.empty()) setup_.mesh_path = fs::absolute(setup_.mesh_path).lexically_normal().string();
}

std::string SolverRuns::key(const ParameterValues& values) const {
  std::string k = setup_hash_;
  for (const auto& [path, v] : values) k += "|" + path + "=" + toml_float(v);
  return k;
}

std::string SolverRuns::entry_name(const ParameterValues& values) const {
  return setup_.entry_prefix + sha256_hex(key(values)).substr(0, 20);
}

std::string SolverRuns::entry_path(const std::string& entry) const { return (fs::path(setup_.cache_dir) / entry).string(); }
std::string SolverRuns::failed_path(const std::string& entry) const {
  return (fs::path(setup_.cache_dir) / ("failed-" + entry)).string();
}

bool SolverRuns::complete(const ParameterValues& values) const {
  const fs::path entry = entry_path(entry_name(values));
  return fs::exists(entry / "key.txt") && read_text_file((entry / "key.txt").string()) == key(values);
}

std::string SolverRuns::command_in(const std::string& dir) const {
  const fs::path d(dir);
  return substitute(setup_.command, {{"case", shell_quote((d / "case.toml").string())},
                                     {"out", shell_quote((d / "result.h5").string())},
                                     {"mesh", shell_quote(setup_.mesh_path)},
                                     {"dir", shell_quote(d.string())}});
}

double SolverRuns::run(const ParameterValues& values, const std::string& label,
                       const std::function<void(const std::string&, const std::string&)>& finish) {
  const std::string name = entry_name(values);
  const std::string k = key(values);
  const fs::path entry = entry_path(name);
  // The run's folder is .tmp-<entry>: the solver writes its own command line (and so this folder's
  // name) into its outputs, and the same run must write the same bytes. Another process running the
  // same entry into a shared cache (or a folder left by a killed run) holds that name: then a name
  // of this process's own.
  static std::atomic<unsigned> counter{0};
  fs::path tmp = fs::path(setup_.cache_dir) / fmt::format(".tmp-{}", name);
  std::error_code ec_made;
  fs::create_directories(setup_.cache_dir, ec_made);
  const bool own_name = !ec_made && fs::create_directory(tmp, ec_made) && !ec_made;  // created here, empty
  if (!own_name) {
    tmp = fs::path(setup_.cache_dir) / fmt::format(".tmp-{}-{}-{}", name, ::getpid(), counter++);
    fs::remove_all(tmp);
    fs::create_directories(tmp);
  }
  const fs::path failed = failed_path(name);
  // Whatever happens below, no temporary folder stays: it becomes the entry, or failed-<entry>
  // for a failed run (the error names it), or it is removed.
  RemoveAtExit guard(tmp);
  auto fail = [&](const std::string& what) {
    std::error_code ec;
    fs::remove_all(failed, ec);
    try {
      write_text_file((tmp / "error.txt").string(), what + "\n");
    } catch (const ComputeError&) {
    }
    fs::rename(tmp, failed, ec);
    return ComputeError(fmt::format("{}: {} ({})", label, what, ec ? tmp.string() + " removed" : "kept in " + failed.string()));
  };
  write_text_file((tmp / "case.toml").string(), setup_.case_template->render(values));
  write_text_file((tmp / "inputs.txt").string(), inputs_);
  const fs::path out = tmp / "result.h5";
  // The record names the entry's own folder, not the temporary one (whose name holds the process
  // id): the same run writes the same bytes.
  write_text_file((tmp / "command.sh").string(), command_in(entry.string()) + "\n");
  const auto r = run_shell(command_in(tmp.string()), tmp.string(), (tmp / "solver.log").string());
  if (r.exit_code != 0)
    throw fail(fmt::format("the solver exited with code {}: {}", r.exit_code, last_line((tmp / "solver.log").string())));
  if (!fs::exists(out)) throw fail("the solver wrote no result.h5 (the command must write {out})");
  try {
    finish(tmp.string(), out.string());
  } catch (const InputError& e) {
    throw fail(fmt::format("cannot read the solver's outputs: {}", e.what()));
  } catch (const ComputeError& e) {
    throw fail(e.what());
  }
  // entry.json holds what the entry depends on, nothing that changes from run to run: the wall time
  // goes to timing.txt (and stderr).
  write_text_file((tmp / "entry.json").string(), entry_json(k, values, setup_.command, ""));
  write_text_file((tmp / "timing.txt").string(), fmt::format("solver_seconds {:.3f}\n", r.seconds));
  if (!setup_.keep_results) {
    fs::remove(out);
    fs::remove(fs::path(out).replace_extension(".xdmf"));
  }
  install_entry(tmp, entry, failed, k, guard);
  return r.seconds;
}

bool SolverRuns::store_derived(const ParameterValues& values, const std::string& derived_from,
                               const std::function<bool(const std::string&)>& fill) {
  const std::string name = entry_name(values), k = key(values);
  const fs::path entry = entry_path(name);
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = fs::path(setup_.cache_dir) / fmt::format(".tmp-{}-derived-{}-{}", name, ::getpid(), counter++);
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  RemoveAtExit guard(tmp);
  if (!fill(tmp.string())) return false;
  write_text_file((tmp / "case.toml").string(), setup_.case_template->render(values));
  write_text_file((tmp / "inputs.txt").string(), inputs_);
  write_text_file((tmp / "entry.json").string(), entry_json(k, values, setup_.command, derived_from));
  install_entry(tmp, entry, failed_path(name), k, guard);
  return true;
}

}  // namespace ugs::runner
