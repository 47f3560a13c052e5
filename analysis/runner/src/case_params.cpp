#include "ugs/runner/case_params.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>
#include <unistd.h>
#include <fstream>
#include <map>
#include <optional>
#include <tuple>
#include <sstream>

#include <fmt/format.h>
#include <toml.hpp>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/toml_reader.hpp"
#include "remove_at_exit.hpp"

namespace ugs::runner {

namespace fs = std::filesystem;

namespace {

// The one finite-number parser of option and case text (formats/csv.hpp).
bool to_double(std::string_view s, double& v) {
  const auto parsed = parse_finite_number(s);
  if (parsed) v = *parsed;
  return parsed.has_value();
}

struct Segment {
  std::string key;
  bool is_index = false;
  std::size_t index = 0;
};

// Splits "material.\"Pool C\".K_m_per_s[0]" into key / name / index segments.
std::vector<Segment> split_path(const std::string& path, const std::string& where) {
  std::vector<Segment> out;
  std::string cur;
  bool quoted = false, have = false;
  auto flush = [&] {
    if (!have) throw InputError(where, fmt::format("parameter path '{}' has an empty part", path));
    out.push_back({cur});
    cur.clear();
    have = false;
  };
  for (std::size_t i = 0; i < path.size(); ++i) {
    const char c = path[i];
    if (quoted) {
      if (c == '"')
        quoted = false;
      else
        cur += c;
      continue;
    }
    if (c == '"') {
      quoted = have = true;
    } else if (c == '.') {
      flush();
    } else if (c == '[') {
      const auto close = path.find(']', i);
      if (close == std::string::npos) throw InputError(where, fmt::format("parameter path '{}': missing ']'", path));
      if (have) flush();
      Segment s;
      s.is_index = true;
      const std::string num = path.substr(i + 1, close - i - 1);
      const auto [e, ec] = std::from_chars(num.data(), num.data() + num.size(), s.index);
      if (num.empty() || ec != std::errc() || e != num.data() + num.size())
        throw InputError(where, fmt::format("parameter path '{}': '[{}]' is not an index", path, num));
      out.push_back(s);
      i = close;
      if (i + 1 < path.size() && path[i + 1] == '.') ++i;
    } else {
      cur += c;
      have = true;
    }
  }
  if (quoted) throw InputError(where, fmt::format("parameter path '{}': unbalanced quote", path));
  if (have) flush();
  if (out.empty()) throw InputError(where, "empty parameter path");
  return out;
}

std::string names_of(const toml::array& a) {
  std::string s;
  for (const auto& e : a)
    if (e.is_table() && e.contains("name") && e.at("name").is_string())
      s += (s.empty() ? "" : ", ") + e.at("name").as_string().str;
  return s.empty() ? "none named" : s;
}

const toml::value& lookup(const toml::value& root, const std::string& path, const std::string& file) {
  const auto segs = split_path(path, file);
  const toml::value* cur = &root;
  std::string so_far;
  auto missing = [&](const std::string& why) {
    return InputError(file, fmt::format("no parameter '{}' in the case: {}", path, why));
  };
  for (const auto& s : segs) {
    const std::string here = so_far.empty() ? s.key : so_far + "." + s.key;
    if (s.is_index) {
      if (!cur->is_array()) throw missing(fmt::format("'{}' is not an array", so_far));
      const auto& a = cur->as_array();
      if (s.index >= a.size()) throw missing(fmt::format("'{}' has {} entries", so_far, a.size()));
      cur = &a[s.index];
      so_far += fmt::format("[{}]", s.index);
      continue;
    }
    if (cur->is_table()) {
      if (!cur->contains(s.key)) {
        std::string keys;
        for (const auto& [k, v] : cur->as_table()) keys += (keys.empty() ? "" : ", ") + k;
        throw missing(so_far.empty() ? fmt::format("no key '{}'", s.key)
                                     : fmt::format("'{}' has no key '{}' (keys: {})", so_far, s.key, keys));
      }
      cur = &cur->at(s.key);
    } else if (cur->is_array()) {
      const auto& a = cur->as_array();
      const toml::value* found = nullptr;
      for (const auto& e : a)
        if (e.is_table() && e.contains("name") && e.at("name").is_string() && e.at("name").as_string().str == s.key) {
          found = &e;
          break;
        }
      if (!found) {
        std::size_t idx = 0;
        const auto [e, ec] = std::from_chars(s.key.data(), s.key.data() + s.key.size(), idx);
        if (ec == std::errc() && e == s.key.data() + s.key.size() && idx < a.size()) found = &a[idx];
      }
      if (!found) throw missing(fmt::format("no [[{}]] named '{}' (names: {})", so_far, s.key, names_of(a)));
      cur = found;
    } else {
      throw missing(fmt::format("'{}' is a value, not a table", so_far));
    }
    so_far = here;
  }
  // A constant given as a field ({ grdecl = ..., scale = ... }): the parameter is its scale factor.
  if (cur->is_table()) {
    bool field = false;
    for (const char* source : {"grdecl", "init", "elevation_table", "depth_table", "map", "cells"}) field = field || cur->contains(source);
    if (field) {
      if (!cur->contains("scale"))
        throw missing("it is a field; write scale = 1.0 in its { ... } for the factor a parameter varies");
      cur = &cur->at("scale");
    }
  }
  if (!cur->is_floating() && !cur->is_integer()) throw missing("it is not a number");
  if (cur->is_floating() && !std::isfinite(cur->as_floating()))
    throw InputError(fmt::format("{}:{}", file, cur->location().line()),
                     fmt::format("'{}' = {} (expected a finite number)", path, cur->as_floating()));
  return *cur;
}

void collect_strings(const toml::value& v, std::vector<const toml::value*>& out) {
  if (v.is_string())
    out.push_back(&v);
  else if (v.is_table())
    for (const auto& [k, e] : v.as_table()) collect_strings(e, out);
  else if (v.is_array())
    for (const auto& e : v.as_array()) collect_strings(e, out);
}

std::string toml_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

}  // namespace

std::vector<std::string> check_parameters(const CaseTemplate& tmpl, const std::vector<ParameterSpec>& params,
                                          const std::string& source) {
  auto where = [&](const ParameterSpec& p) { return source.empty() ? "parameter to calibrate " + p.name : source; };
  // Each path names a number of the case, and no number is named twice: neither by the same text
  // nor by two spellings of it (material.pool_c.c_R, material."pool_c".c_R, material.4.c_R), which
  // would set it from two parameters, or twice in one copy.
  std::set<std::string> seen;
  std::map<std::pair<std::size_t, std::size_t>, std::string> at;  // (line, column) of the value -> its first path
  std::istringstream in(tmpl.text());
  const toml::value root = toml::parse(in, tmpl.path());
  for (const auto& p : params)
    for (const auto& path : p.paths) {
      const auto loc = lookup(root, path, tmpl.path()).location();
      if (!seen.insert(path).second) throw InputError(where(p), fmt::format("'{}' is named twice", path));
      const auto [it, fresh] = at.emplace(std::make_pair(loc.line(), loc.column()), path);
      if (!fresh)
        throw InputError(where(p), fmt::format("'{}' and '{}' name the same value of the case ({}:{}; expected each value named once)",
                                               it->second, path, tmpl.path(), loc.line()));
    }
  std::vector<std::string> warnings;
  // Each copy is checked at both ends of each parameter (read_rendered_case).
  for (const auto& p : params) {
    const double now = tmpl.value(p.paths.front());
    if (now < p.lower || now > p.upper)
      warnings.push_back(fmt::format("{} = {} in the case lies outside the range {}:{}", p.paths.front(), now, p.lower, p.upper));
    for (double bound : {p.lower, p.upper}) {
      std::vector<std::pair<std::string, double>> v;
      for (const auto& path : p.paths) v.emplace_back(path, bound);
      try {
        (void)read_rendered_case(tmpl, v);
      } catch (const InputError& e) {
        throw InputError(where(p), fmt::format("the case is not valid at {} = {}: {}", p.name, bound, e.what()));
      }
    }
  }
  return warnings;
}

CaseFile read_rendered_case(const CaseTemplate& tmpl, const std::vector<std::pair<std::string, double>>& values) {
  // The case reader takes a file: the copy goes to the system's temporary folder and is always
  // removed (no output or cache folder may exist yet).
  std::string copy = (fs::temp_directory_path() / fmt::format("ugs-case-copy-{}-XXXXXX", ::getpid())).string();
  const int fd = ::mkstemp(copy.data());
  if (fd < 0) throw ComputeError(fmt::format("cannot create a temporary file in {}", fs::temp_directory_path().string()));
  ::close(fd);
  const RemoveAtExit remove_copy(copy);
  {
    std::ofstream f(copy);
    f << tmpl.render(values);
  }
  try {
    return read_case_file(copy);
  } catch (const InputError& e) {
    // Every problem names the copy (one per line of an ErrorList): name the case instead.
    std::string msg = e.what();
    for (auto at = msg.find(copy); at != std::string::npos; at = msg.find(copy, at + tmpl.path().size()))
      msg.replace(at, copy.size(), tmpl.path());
    throw InputError("", msg);
  }
}

std::string toml_float(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

ParameterSpec parse_parameter(const std::string& text) {
  const std::string where = "parameter to calibrate " + text;
  const auto eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(where, "expected PATH=LOWER:UPPER (e.g. material.pool_c.c_R=2:6)");
  ParameterSpec p;
  p.name = text.substr(0, eq);
  std::string paths = p.name, cur;
  for (char c : paths + ",") {
    if (c == ',') {
      if (cur.empty()) throw InputError(where, "empty parameter path");
      p.paths.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  std::string range = text.substr(eq + 1);
  if (range.size() > 4 && range.substr(range.size() - 4) == ":log") {
    p.log_scale = true;
    range.resize(range.size() - 4);
  }
  const auto colon = range.find(':');
  if (colon == std::string::npos || !to_double(std::string_view(range).substr(0, colon), p.lower) ||
      !to_double(std::string_view(range).substr(colon + 1), p.upper))
    throw InputError(where, fmt::format("'{}' is not LOWER:UPPER (e.g. 2:6, or 1e-8:1e-6:log)", text.substr(eq + 1)));
  if (!(p.lower < p.upper))
    throw InputError(where, fmt::format("lower bound {} is not below upper bound {} (bounds reversed?)", p.lower, p.upper));
  if (p.log_scale && p.lower <= 0) throw InputError(where, "a log-scale parameter needs positive bounds");
  return p;
}

CaseTemplate::CaseTemplate(const std::string& case_path) : path_(case_path) {
  std::error_code ec;
  if (fs::is_directory(case_path, ec)) throw InputError(case_path, "is a folder (expected a TOML case file)");
  std::ifstream f(case_path, std::ios::binary);
  if (!f) throw InputError(case_path, "cannot open the case file");
  std::stringstream ss;
  ss << f.rdbuf();
  text_ = ss.str();
  // The tools' one TOML reader: text that is not UTF-8 or a syntax error is one line,
  // "case.toml:LINE: TOML syntax error: ...".
  (void)TomlTable::parse_file(case_path);
}

double CaseTemplate::value(const std::string& path) const {
  std::istringstream in(text_);
  const toml::value root = toml::parse(in, path_);
  const auto& v = lookup(root, path, path_);
  return v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer());
}

std::vector<std::string> CaseTemplate::referenced_files() const {
  std::istringstream in(text_);
  const toml::value root = toml::parse(in, path_);
  std::vector<const toml::value*> strings;
  collect_strings(root, strings);
  const fs::path dir = fs::absolute(fs::path(path_)).parent_path();
  std::vector<std::string> files;
  for (const toml::value* s : strings) {
    const std::string& str = s->as_string().str;
    if (str.empty()) continue;
    const fs::path full = fs::path(str).is_absolute() ? fs::path(str) : dir / str;
    std::error_code ec;
    if (fs::is_regular_file(full, ec)) files.push_back(fs::weakly_canonical(full, ec).string());
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

std::string CaseTemplate::render(const std::vector<std::pair<std::string, double>>& values) const {
  std::istringstream in(text_);
  const toml::value root = toml::parse(in, path_);
  // Edits per line: (column, length, replacement); the value's text must be where toml11 says.
  std::map<std::size_t, std::vector<std::tuple<std::size_t, std::size_t, std::string>>> edits;
  std::map<std::pair<std::size_t, std::size_t>, std::pair<std::string, double>> set_by;  // (line, column) -> (path, value)
  std::vector<std::string> lines;
  {
    std::size_t start = 0;
    while (start <= text_.size()) {
      const auto nl = text_.find('\n', start);
      if (nl == std::string::npos) {
        lines.push_back(text_.substr(start));
        break;
      }
      lines.push_back(text_.substr(start, nl - start + 1));
      start = nl + 1;
    }
  }
  auto region_text = [&](const toml::source_location& loc) -> std::optional<std::string> {
    if (loc.line() < 1 || loc.line() > lines.size()) return std::nullopt;
    const std::string& l = lines[loc.line() - 1];
    if (loc.column() < 1 || loc.column() - 1 + loc.region() > l.size()) return std::nullopt;
    return l.substr(loc.column() - 1, loc.region());
  };
  for (const auto& [p, v] : values) {
    const auto& val = lookup(root, p, path_);
    const auto loc = val.location();
    const auto t = region_text(loc);
    double old = 0;
    const double cur = val.is_floating() ? val.as_floating() : static_cast<double>(val.as_integer());
    std::string tt = t ? *t : "";
    tt.erase(std::remove(tt.begin(), tt.end(), '_'), tt.end());
    if (!t || !to_double(tt, old) || old != cur)
      throw InputError(path_, fmt::format("cannot locate the text of parameter '{}' (line {})", p, loc.line()));
    // Two spellings of one value (material.pool_c.c_R, material."pool_c".c_R): one edit, or the
    // second would replace the first's text again ("3.0" -> "2.25" -> "2.255").
    const auto [it, fresh] = set_by.emplace(std::make_pair(loc.line(), loc.column()), std::make_pair(p, v));
    if (!fresh) {
      if (it->second.second != v)
        throw InputError(fmt::format("{}:{}", path_, loc.line()),
                         fmt::format("'{}' and '{}' name the same value, set to {} and {} (expected each value named once)",
                                     it->second.first, p, toml_float(it->second.second), toml_float(v)));
      continue;
    }
    edits[loc.line()].emplace_back(loc.column() - 1, loc.region(), toml_float(v));
  }
  // File names relative to the case's folder: absolute in the copy.
  std::vector<const toml::value*> strings;
  collect_strings(root, strings);
  const fs::path dir = fs::absolute(fs::path(path_)).parent_path();
  for (const toml::value* s : strings) {
    const std::string& str = s->as_string().str;
    if (str.empty() || fs::path(str).is_absolute()) continue;
    std::error_code ec;
    const fs::path full = dir / str;
    if (!fs::is_regular_file(full, ec)) continue;
    const auto loc = s->location();
    const auto t = region_text(loc);
    if (!t || t->size() < 2 || (t->front() != '"' && t->front() != '\'') || t->back() != t->front()) continue;
    edits[loc.line()].emplace_back(loc.column() - 1, loc.region(), toml_string(fs::weakly_canonical(full).string()));
  }
  for (auto& [line, list] : edits) {
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
    for (const auto& [col, len, rep] : list) lines[line - 1].replace(col, len, rep);
  }
  std::string out;
  for (const auto& l : lines) out += l;
  return out;
}

}  // namespace ugs::runner
