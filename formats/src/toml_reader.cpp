#include "ugs/formats/toml_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace ugs {
namespace {
std::string type_name(const toml::value& v) {
  switch (v.type()) {
    case toml::value_t::boolean: return "a boolean";
    case toml::value_t::integer: return "an integer";
    case toml::value_t::floating: return "a number";
    case toml::value_t::string: return "a string";
    case toml::value_t::array: return "an array";
    case toml::value_t::table: return "a table";
    default: return "a date/time";
  }
}

// Every float of a document must be finite: TOML allows inf and nan, no input of ours means them.
// `key` is the dotted path of `v` ("water.compressibility_per_MPa", "material[1].K_m_per_s[0]").
void reject_non_finite(const toml::value& v, const std::string& key, const std::string& file) {
  if (v.is_floating()) {
    const double x = v.as_floating();
    if (!std::isfinite(x)) {
      const auto line = v.location().line();
      throw InputError(line > 0 ? fmt::format("{}:{}", file, line) : file,
                       fmt::format("{} = {} is not a finite number", key, x));
    }
  } else if (v.is_array()) {
    std::size_t i = 0;
    for (const auto& e : v.as_array()) reject_non_finite(e, fmt::format("{}[{}]", key, i++), file);
  } else if (v.is_table()) {
    for (const auto& [name, e] : v.as_table()) reject_non_finite(e, key.empty() ? name : key + "." + name, file);
  }
}
}  // namespace

void require_utf8(const std::string& text, const std::string& file) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    std::size_t len = 0;
    unsigned char lo = 0x80, hi = 0xbf;  // the allowed range of the second byte
    if (c < 0x80) len = 1;
    else if (c >= 0xc2 && c <= 0xdf) len = 2;
    else if (c == 0xe0) len = 3, lo = 0xa0;
    else if (c >= 0xe1 && c <= 0xec) len = 3;
    else if (c == 0xed) len = 3, hi = 0x9f;
    else if (c >= 0xee && c <= 0xef) len = 3;
    else if (c == 0xf0) len = 4, lo = 0x90;
    else if (c >= 0xf1 && c <= 0xf3) len = 4;
    else if (c == 0xf4) len = 4, hi = 0x8f;
    bool ok = len > 0 && i + len <= n;
    for (std::size_t k = 1; ok && k < len; ++k)
      ok = k == 1 ? s[i + k] >= lo && s[i + k] <= hi : s[i + k] >= 0x80 && s[i + k] <= 0xbf;
    if (!ok)
      throw InputError(fmt::format("{}:{}", file, line),
                       fmt::format("byte 0x{:02x} at column {} is not UTF-8 (expected a UTF-8 text file)", c, i - line_start + 1));
    if (c == '\n') line += 1, line_start = i + 1;
    i += len;
  }
}

TomlTable TomlTable::parse_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory (expected a TOML file)");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, fmt::format("cannot open: {}", std::strerror(errno)));
  std::stringstream text;
  text << f.rdbuf();
  require_utf8(text.str(), path);
  try {
    toml::value doc = toml::parse(text, path);
    reject_non_finite(doc, "", path);
    return TomlTable(std::move(doc), path, "");
  } catch (const toml::syntax_error& e) {
    std::string msg = e.what();
    // toml11's message is multi-line; keep its first line.
    const auto nl = msg.find('\n');
    if (nl != std::string::npos) msg = msg.substr(0, nl);
    if (msg.rfind("[error] ", 0) == 0) msg = msg.substr(8);
    throw InputError(path + ":" + std::to_string(e.location().line()), "TOML syntax error: " + msg);
  }
}

TomlTable::TomlTable(toml::value v, std::string file, std::string path_in_doc)
    : v_(std::move(v)), file_(std::move(file)), path_(std::move(path_in_doc)) {}

std::string TomlTable::where() const {
  const auto loc = v_.location();
  return loc.line() > 0 && !path_.empty() ? fmt::format("{}:{}", file_, loc.line()) : file_;
}

std::string TomlTable::where(const std::string& key) const {
  if (!v_.is_table() || !v_.as_table().count(key)) return where();
  return fmt::format("{}:{}", file_, v_.as_table().at(key).location().line());
}

InputError TomlTable::error(const std::string& key, const std::string& message) const {
  const std::string full = path_.empty() ? key : path_ + "." + key;
  return InputError(where(key), fmt::format("'{}': {}", full, message));
}

bool TomlTable::has(const std::string& key) const { return v_.is_table() && v_.as_table().count(key) > 0; }

const toml::value& TomlTable::at(const std::string& key) const {
  if (!has(key)) throw InputError(where(), fmt::format("'{}' is missing", path_.empty() ? key : path_ + "." + key));
  return v_.as_table().at(key);
}

double TomlTable::number(const std::string& key) const {
  const auto& v = at(key);
  if (v.is_floating()) return v.as_floating();
  if (v.is_integer()) return static_cast<double>(v.as_integer());
  throw error(key, "expected a number, got " + type_name(v));
}

std::optional<double> TomlTable::number_opt(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return number(key);
}

long long TomlTable::integer(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_integer()) throw error(key, "expected an integer, got " + type_name(v));
  return v.as_integer();
}

std::optional<long long> TomlTable::integer_opt(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return integer(key);
}

std::string TomlTable::string(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_string()) throw error(key, "expected a string, got " + type_name(v));
  return v.as_string().str;
}

std::optional<std::string> TomlTable::string_opt(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return string(key);
}

bool TomlTable::boolean_or(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const auto& v = at(key);
  if (!v.is_boolean()) throw error(key, "expected true or false, got " + type_name(v));
  return v.as_boolean();
}

std::vector<double> TomlTable::numbers(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_array()) throw error(key, "expected an array of numbers, got " + type_name(v));
  std::vector<double> r;
  for (const auto& e : v.as_array()) {
    if (e.is_floating()) r.push_back(e.as_floating());
    else if (e.is_integer()) r.push_back(static_cast<double>(e.as_integer()));
    else throw error(key, "expected an array of numbers, found " + type_name(e));
  }
  return r;
}

std::vector<std::vector<double>> TomlTable::number_rows(const std::string& key, std::size_t width,
                                                        std::vector<std::string>* row_where) const {
  const auto& v = at(key);
  const std::string shape = fmt::format("an array of rows [{}]", width == 2 ? "depth_m, value" : "numbers");
  if (!v.is_array()) throw error(key, fmt::format("expected {}, got {}", shape, type_name(v)));
  if (v.as_array().empty()) throw error(key, fmt::format("is empty (expected {})", shape));
  std::vector<std::vector<double>> rows;
  for (const auto& row : v.as_array()) {
    const std::string at_row = row.location().line() > 0 ? fmt::format("{}:{}", file_, row.location().line()) : where(key);
    const std::string name = fmt::format("'{}' row {}", path_.empty() ? key : path_ + "." + key, rows.size() + 1);
    if (!row.is_array() || row.as_array().size() != width)
      throw InputError(at_row, fmt::format("{}: expected {} numbers [{}], got {}", name, width,
                                           width == 2 ? "depth_m, value" : "...",
                                           row.is_array() ? std::to_string(row.as_array().size()) + " values" : type_name(row)));
    std::vector<double> r;
    for (const auto& e : row.as_array()) {
      if (e.is_floating()) r.push_back(e.as_floating());
      else if (e.is_integer()) r.push_back(static_cast<double>(e.as_integer()));
      else throw InputError(at_row, fmt::format("{}: expected numbers, found {}", name, type_name(e)));
    }
    rows.push_back(std::move(r));
    if (row_where) row_where->push_back(at_row);
  }
  return rows;
}

std::vector<std::string> TomlTable::strings(const std::string& key) const {
  const auto& v = at(key);
  if (v.is_string()) return {v.as_string().str};
  if (!v.is_array()) throw error(key, "expected an array of strings, got " + type_name(v));
  std::vector<std::string> r;
  for (const auto& e : v.as_array()) {
    if (!e.is_string()) throw error(key, "expected an array of strings, found " + type_name(e));
    r.push_back(e.as_string().str);
  }
  return r;
}

std::optional<TomlTable> TomlTable::table_opt(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return table(key);
}

TomlTable TomlTable::table(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_table()) throw error(key, "expected a table, got " + type_name(v));
  return TomlTable(v, file_, path_.empty() ? key : path_ + "." + key);
}

bool TomlTable::is_table(const std::string& key) const { return has(key) && at(key).is_table(); }

std::vector<TomlTable> TomlTable::items(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_array()) throw error(key, "expected an array, got " + type_name(v));
  std::vector<TomlTable> r;
  std::size_t i = 0;
  for (const auto& e : v.as_array()) r.emplace_back(e, file_, fmt::format("{}[{}]", path_.empty() ? key : path_ + "." + key, i++));
  return r;
}

std::optional<double> TomlTable::as_number() const {
  if (v_.is_floating()) return v_.as_floating();
  if (v_.is_integer()) return static_cast<double>(v_.as_integer());
  return std::nullopt;
}

std::vector<TomlTable> TomlTable::tables(const std::string& key) const {
  std::vector<TomlTable> r;
  if (!has(key)) return r;
  const auto& v = at(key);
  if (!v.is_array()) throw error(key, "expected [[" + key + "]] tables, got " + type_name(v));
  std::size_t i = 0;
  for (const auto& e : v.as_array()) {
    if (!e.is_table()) throw error(key, "expected [[" + key + "]] tables, found " + type_name(e));
    r.emplace_back(e, file_, fmt::format("{}[{}]", path_.empty() ? key : path_ + "." + key, i++));
  }
  return r;
}

std::vector<std::string> TomlTable::keys() const {
  std::vector<std::string> k;
  if (v_.is_table())
    for (const auto& [name, _] : v_.as_table()) k.push_back(name);
  return k;
}

void TomlTable::reject_unknown(const std::set<std::string>& known) const {
  for (const auto& k : keys())
    if (!known.count(k)) {
      std::string list;
      for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
      throw error(k, "unknown key (known here: " + list + ")");
    }
}

void TomlTable::reject_unknown(const std::set<std::string>& known, ErrorList& errors) const {
  for (const auto& k : keys())
    if (!known.count(k)) {
      std::string list;
      for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
      errors.add(error(k, "unknown key (known here: " + list + ")"));
    }
}

std::string resolve_relative(const std::string& base_file, const std::string& relative) {
  namespace fs = std::filesystem;
  const fs::path r(relative);
  if (r.is_absolute()) return relative;
  return (fs::path(base_file).parent_path() / r).lexically_normal().string();
}

}  // namespace ugs
