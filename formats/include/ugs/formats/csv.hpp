// CSV tables (schedules, PS points, sampled series): a reader giving columns by name with typed
// access and errors that name the file and line, a writer going through OutputFile, and the ISO
// 8601 dates every table uses.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ugs/formats/io.hpp"

namespace ugs {

// ---- dates ------------------------------------------------------------------------------------
// Days since 1970-01-01 in the proleptic Gregorian calendar (negative before 1970).
std::int64_t days_from_civil(std::int64_t year, int month, int day);
struct CivilDate {
  std::int64_t year;
  int month, day;
};
CivilDate civil_from_days(std::int64_t days);

// Seconds since 1970-01-01T00:00:00 UTC for "YYYY-MM-DD", "YYYY-MM-DDThh:mm[:ss]" (a space may
// stand for the T, a trailing Z is allowed) or "YYYYMMDD"; nullopt if `text` is none of these
// or not a valid date.
std::optional<std::int64_t> parse_iso_date(std::string_view text);
// A finite number written in option or case text: spaces around it and a leading '+' allowed, the
// whole text read (from_chars: no locale); nullopt for anything else, nan and inf included.
std::optional<double> parse_finite_number(std::string_view text);
// "YYYY-MM-DD" when the time of day is midnight, "YYYY-MM-DDThh:mm:ss" otherwise.
std::string format_iso_date(std::int64_t seconds);

// ---- reading ----------------------------------------------------------------------------------
// A whole table in memory. The first non-comment line is the header; fields are separated by
// commas, may be quoted ("a, b" and "" for a quote, also across lines), and unquoted fields are
// trimmed. Lines starting with '#' and blank lines are skipped. Every row must have as many
// fields as the header.
class CsvTable {
public:
  static CsvTable read(InputStream& in);
  static CsvTable read(const std::string& path);  // "-" = stdin

  const std::string& name() const { return name_; }
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return line_of_row_.size(); }

  std::optional<std::size_t> find_column(std::string_view column) const;
  // Index of `column`; InputError "file.csv: no column 'p_MPa' (columns: date, q_m3)" if absent.
  std::size_t column(std::string_view column) const;

  std::string_view text(std::size_t row, std::size_t col) const {
    const std::size_t i = row * columns_.size() + col;
    const std::size_t begin = i == 0 ? 0 : cell_end_[i - 1];
    return std::string_view(text_).substr(begin, cell_end_[i] - begin);
  }
  // A finite number; InputError("file.csv:LINE", "column 'p_MPa': 'abc' is not a number") otherwise.
  double number(std::size_t row, std::size_t col) const;
  std::int64_t integer(std::size_t row, std::size_t col) const;
  // A date (see parse_iso_date) as seconds since 1970.
  std::int64_t date(std::size_t row, std::size_t col) const;
  // The whole column, each value checked as above.
  std::vector<double> numbers(std::string_view column) const;
  std::vector<std::int64_t> dates(std::string_view column) const;

  // Line of the input a row came from, and the matching error location "file.csv:LINE".
  std::size_t line_of(std::size_t row) const { return line_of_row_[row]; }
  std::string where(std::size_t row) const;

private:
  InputError cell_error(std::size_t row, std::size_t col, std::string_view what) const;

  std::string name_;
  std::vector<std::string> columns_;
  std::string text_;                        // all cells, row-major, back to back (one allocation,
  std::vector<std::size_t> cell_end_;       // not one per cell: PS tables have millions of cells)
  std::vector<std::size_t> line_of_row_;
};

// ---- writing ----------------------------------------------------------------------------------
// Writes a header, then rows cell by cell; the file appears only on commit() ("-" = stdout).
//   CsvWriter w("uz.csv", {"date", "uz_mm"});
//   w.date(t).number(uz * 1e3, 3).end_row();
//   w.commit();
class CsvWriter {
public:
  CsvWriter(const std::string& path, std::vector<std::string> columns, std::span<const std::string> comments = {});

  CsvWriter& text(std::string_view s);       // quoted when it holds a comma, quote or line break
  CsvWriter& number(double v);               // shortest text that reads back to the same double
  CsvWriter& number(double v, int decimals); // fixed decimals, e.g. mm to 3
  CsvWriter& integer(std::int64_t v);
  CsvWriter& date(std::int64_t seconds);     // format_iso_date
  void end_row();                            // throws std::logic_error if the row is not full
  void commit();

private:
  void cell(std::string_view s);
  OutputFile out_;
  std::size_t ncolumns_;
  std::size_t in_row_ = 0;
  std::string buf_;
};

}  // namespace ugs
