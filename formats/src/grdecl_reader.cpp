#include "ugs/formats/grdecl.hpp"

#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs {
namespace {

// Keywords that take no values (and no '/'): the section headers and switches a GRDECL holds.
bool without_values(const std::string& k) {
  static const std::set<std::string> none = {"RUNSPEC", "GRID",    "EDIT",   "PROPS",  "REGIONS", "SOLUTION", "SUMMARY", "SCHEDULE",
                                             "ECHO",    "NOECHO", "NOGGF", "INIT",   "NEWTRAN", "OLDTRAN",  "END",     "FAULTS_END"};
  return none.count(k) > 0;
}

// Keywords of several records, each closed by '/', the list by an empty record: skipped (fault
// names and transmissibility multipliers do not move cells).
bool of_records(const std::string& k) {
  static const std::set<std::string> kw = {"FAULTS", "MULTFLT", "NNC", "EDITNNC", "THPRES"};
  return kw.count(k) > 0;
}

// Keywords that compute arrays from others: refused, since the arrays read would not be the deck's.
bool edits_arrays(const std::string& k) {
  static const std::set<std::string> kw = {"EQUALS", "COPY", "MULTIPLY", "ADD", "MINVALUE", "MAXVALUE", "BOX", "ENDBOX", "OPERATE"};
  return kw.count(k) > 0;
}

bool keyword_like(const std::string& t) {
  if (t.empty() || !std::isalpha(static_cast<unsigned char>(t[0]))) return false;
  for (char c : t)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '+') return false;
  return t.size() <= 8;
}

class Reader {
public:
  Reader(const std::set<std::string>& values_of, GrdeclFile& out) : values_of_(values_of), out_(out) {}

  void read(const std::string& path, int depth) {
    if (depth > 8) throw InputError(path, "INCLUDE nested more than 8 deep");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "no such file (expected a GRDECL file)");
    std::ifstream f(path, std::ios::binary);
    if (!f) throw InputError(path, "cannot open");
    std::string line;
    std::size_t n = 0;
    GrdeclKeyword* open = nullptr;
    bool keep = false, include = false;
    std::string include_where;
    while (std::getline(f, line)) {
      ++n;
      const std::string where = fmt::format("{}:{}", path, n);
      if (const auto c = line.find("--"); c != std::string::npos) line.resize(c);
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i >= line.size()) break;
        std::string tok;
        if (line[i] == '\'' || line[i] == '"') {
          const char q = line[i];
          const auto e = line.find(q, i + 1);
          if (e == std::string::npos) throw InputError(where, "unclosed quote");
          tok = line.substr(i, e - i + 1);
          i = e + 1;
        } else if (line[i] == '/') {
          tok = "/";
          ++i;
        } else {
          const std::size_t b = i;
          while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])) && line[i] != '/') ++i;
          tok = line.substr(b, i - b);
        }
        if (records_) {
          // Inside a keyword of records: an empty record ends it.
          if (tok == "/") {
            if (record_items_ == 0) records_ = false;
            record_items_ = 0;
          } else {
            ++record_items_;
          }
          continue;
        }
        if (!open) {
          if (tok == "/") continue;
          std::string name = tok;
          for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
          if (!keyword_like(name)) throw InputError(where, fmt::format("'{}' where a keyword was expected", tok));
          if (without_values(name)) continue;
          if (edits_arrays(name))
            throw InputError(where, fmt::format("{} computes arrays from others, which is not read here (export the arrays "
                                                "themselves, e.g. from ResInsight or the geomodel)", name));
          if (of_records(name)) {
            records_ = true;
            record_items_ = 0;
            continue;
          }
          out_.keywords.push_back({name, where, {}, {}});
          open = &out_.keywords.back();
          include = name == "INCLUDE";
          keep = include || values_of_.empty() || values_of_.count(name);
          include_where = where;
          continue;
        }
        if (tok == "/") {
          if (include) {
            if (open->words.size() != 1) throw InputError(open->where, "INCLUDE needs one file name");
            std::string file = open->words[0];
            out_.keywords.pop_back();
            open = nullptr;
            if (file.size() >= 2 && (file.front() == '\'' || file.front() == '"')) file = file.substr(1, file.size() - 2);
            const std::filesystem::path p(file);
            read(p.is_absolute() ? file : (std::filesystem::path(path).parent_path() / p).string(), depth + 1);
          } else if (!keep) {
            out_.keywords.pop_back();
          }
          open = nullptr;
          continue;
        }
        if (!keep) continue;
        if (tok.front() == '\'' || tok.front() == '"') {
          open->words.push_back(tok.substr(1, tok.size() - 2));
          continue;
        }
        // N*value (N*: N defaults, not meaningful in an array of values).
        std::size_t repeat = 1;
        std::string value = tok;
        if (const auto star = tok.find('*'); star != std::string::npos) {
          const char* b = tok.data();
          const auto [e, err] = std::from_chars(b, b + star, repeat);
          if (err != std::errc() || e != b + star || repeat == 0 || repeat > (std::size_t(1) << 32))
            throw InputError(where, fmt::format("'{}' in {}: the repeat count is not a positive integer", tok, open->name));
          value = tok.substr(star + 1);
          if (value.empty())
            throw InputError(where, fmt::format("'{}' in {}: defaulted values (N*) are not a property value", tok, open->name));
        }
        if (const auto v = parse_finite_number(value)) {
          open->values.insert(open->values.end(), repeat, *v);
        } else {
          if (repeat != 1) throw InputError(where, fmt::format("'{}' in {}: not a number", tok, open->name));
          open->words.push_back(value);
        }
      }
      if (out_.keywords.size() > 0 && open && open->values.size() > (std::size_t(1) << 34))
        throw InputError(where, "keyword with more than 2^34 values");
    }
    if (open) throw InputError(open->where, fmt::format("{} has no closing '/' before the end of the file", open->name));
    if (records_) throw InputError(path, "a keyword of records (FAULTS, MULTFLT, ...) has no closing empty record '/'");
  }

private:
  const std::set<std::string>& values_of_;
  GrdeclFile& out_;
  bool records_ = false;         // inside FAULTS, MULTFLT, ...
  std::size_t record_items_ = 0; // items of the current record
};

}  // namespace

const GrdeclKeyword* GrdeclFile::find(const std::string& name) const {
  for (auto it = keywords.rbegin(); it != keywords.rend(); ++it)
    if (it->name == name) return &*it;
  return nullptr;
}

std::string GrdeclFile::names() const {
  std::string s;
  std::set<std::string> seen;
  for (const auto& k : keywords)
    if (seen.insert(k.name).second) s += (s.empty() ? "" : ", ") + k.name;
  return s.empty() ? "none" : s;
}

GrdeclFile read_grdecl(const std::string& path, const std::set<std::string>& values_of) {
  GrdeclFile f;
  f.path = path;
  Reader(values_of, f).read(path, 0);
  return f;
}

}  // namespace ugs
