// Strict reading of TOML input files (case files, stratigraphy files): typed getters that report
// `file:line: key 'x': ...` as ugs::InputError, and unknown keys reported as errors rather than
// silently ignored (a misspelt key must never fall back to a default).
#pragma once
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml.hpp>

#include "ugs/formats/error.hpp"

namespace ugs {

// TOML is UTF-8 (TOML 1.0): InputError "file:LINE: byte 0x9d at column 2 is not UTF-8 (expected a
// UTF-8 text file)" at the first byte that does not start or continue a UTF-8 sequence (overlong
// forms, surrogates and code points above U+10FFFF included). toml11 3.7.1 (Debian's
// libtoml11-dev) reads out of bounds when a literal string or quoted key ('...', '''...''') is not
// valid UTF-8 (its error path rewinds a location with an iterator of another buffer: parser.hpp,
// parse_literal_string, parse_ml_literal_string; found by fuzz_ensemble_spec with the 3 bytes
// '\x9d'), so every text is checked before toml11 sees it.
void require_utf8(const std::string& text, const std::string& file);

class TomlTable {
public:
  // Parses a file (checked with require_utf8 first); syntax errors become InputError with the
  // file and line.
  static TomlTable parse_file(const std::string& path);

  TomlTable(toml::value v, std::string file, std::string path_in_doc);

  const std::string& file() const { return file_; }
  // "file:line" of the table itself or of one of its keys.
  std::string where() const;
  std::string where(const std::string& key) const;
  InputError error(const std::string& key, const std::string& message) const;

  bool has(const std::string& key) const;
  double number(const std::string& key) const;
  std::optional<double> number_opt(const std::string& key) const;
  double number_or(const std::string& key, double fallback) const { return number_opt(key).value_or(fallback); }
  long long integer(const std::string& key) const;
  std::optional<long long> integer_opt(const std::string& key) const;
  std::string string(const std::string& key) const;
  std::optional<std::string> string_opt(const std::string& key) const;
  bool boolean_or(const std::string& key, bool fallback) const;
  std::vector<double> numbers(const std::string& key) const;
  std::vector<std::string> strings(const std::string& key) const;
  // A table of numbers written as an array of rows ([[0, 2000], [500, 2300]]), each `width` long;
  // `row_where` (if given) gets "file:line" of each row, for messages naming the row.
  std::vector<std::vector<double>> number_rows(const std::string& key, std::size_t width,
                                               std::vector<std::string>* row_where = nullptr) const;
  std::optional<TomlTable> table_opt(const std::string& key) const;
  TomlTable table(const std::string& key) const;
  // Whether the value of `key` is a table (an inline table { ... } included).
  bool is_table(const std::string& key) const;
  // The elements of an array, each wrapped (path "key[i]"), whatever their type.
  std::vector<TomlTable> items(const std::string& key) const;
  // For a wrapped element: whether it is a table; its number (nullopt when it is not a number).
  bool is_table() const { return v_.is_table(); }
  std::optional<double> as_number() const;
  // An array of tables ([[name]]); empty if absent.
  std::vector<TomlTable> tables(const std::string& key) const;

  // Throws for the first key of this table not in `known` (after all getters were called).
  void reject_unknown(const std::set<std::string>& known) const;
  // Adds every key of this table not in `known` to `errors` (one line each).
  void reject_unknown(const std::set<std::string>& known, ErrorList& errors) const;
  std::vector<std::string> keys() const;

private:
  const toml::value& at(const std::string& key) const;
  toml::value v_;
  std::string file_, path_;
};

// Resolves `relative` against the directory of `base_file` (absolute paths are returned as is).
std::string resolve_relative(const std::string& base_file, const std::string& relative);

}  // namespace ugs
