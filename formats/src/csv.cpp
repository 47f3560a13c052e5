// CSV tables and ISO 8601 dates. Dates use Howard Hinnant's days-from-civil algorithms, so no
// time zone library or locale is involved and dates before 1970 work.
#include "ugs/formats/csv.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace ugs {

// ---- dates ------------------------------------------------------------------------------------

std::int64_t days_from_civil(std::int64_t y, int m, int d) {
  y -= m <= 2;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t yoe = y - era * 400;                                      // [0, 399]
  const std::int64_t doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;    // [0, 365]
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;              // [0, 146096]
  return era * 146097 + doe - 719468;
}

CivilDate civil_from_days(std::int64_t z) {
  z += 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const int d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  const int m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  return {yoe + era * 400 + (m <= 2), m, d};
}

namespace {

bool is_leap(std::int64_t y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(std::int64_t y, int m) {
  static constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && is_leap(y) ? 29 : days[m - 1];
}

// Reads exactly `n` digits at `pos`.
bool digits(std::string_view s, std::size_t pos, std::size_t n, int& out) {
  if (pos + n > s.size()) return false;
  out = 0;
  for (std::size_t i = pos; i < pos + n; ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    out = out * 10 + (s[i] - '0');
  }
  return true;
}

}  // namespace

std::optional<double> parse_finite_number(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parse_iso_date(std::string_view s) {
  int y, m, d, hh = 0, mm = 0, ss = 0;
  std::size_t pos;
  if (s.size() == 8) {
    if (!digits(s, 0, 4, y) || !digits(s, 4, 2, m) || !digits(s, 6, 2, d)) return std::nullopt;
    pos = 8;
  } else {
    if (!digits(s, 0, 4, y) || s.size() < 10 || s[4] != '-' || !digits(s, 5, 2, m) || s[7] != '-' ||
        !digits(s, 8, 2, d))
      return std::nullopt;
    pos = 10;
    if (pos < s.size() && (s[pos] == 'T' || s[pos] == ' ')) {
      if (!digits(s, pos + 1, 2, hh) || pos + 3 >= s.size() || s[pos + 3] != ':' || !digits(s, pos + 4, 2, mm))
        return std::nullopt;
      pos += 6;
      if (pos < s.size() && s[pos] == ':') {
        if (!digits(s, pos + 1, 2, ss)) return std::nullopt;
        pos += 3;
      }
      if (pos < s.size() && s[pos] == 'Z') ++pos;
    }
  }
  if (pos != s.size()) return std::nullopt;
  if (m < 1 || m > 12 || d < 1 || d > days_in_month(y, m) || hh > 23 || mm > 59 || ss > 59) return std::nullopt;
  return days_from_civil(y, m, d) * 86400 + hh * 3600 + mm * 60 + ss;
}

std::string format_iso_date(std::int64_t seconds) {
  std::int64_t days = seconds / 86400, rest = seconds % 86400;
  if (rest < 0) rest += 86400, --days;  // floor division: 1969-12-31T23:00:00 is day -1
  const CivilDate c = civil_from_days(days);
  if (rest == 0) return fmt::format("{:04}-{:02}-{:02}", c.year, c.month, c.day);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", c.year, c.month, c.day, rest / 3600, rest / 60 % 60,
                     rest % 60);
}

// ---- reading ----------------------------------------------------------------------------------

namespace {

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

bool skippable(std::string_view line) {
  const std::string_view t = trim(line);
  return t.empty() || t.front() == '#';
}

// Reads one record (possibly several lines when a quoted field holds line breaks) into `fields`.
// Returns false at end of input; `start_line` is where the record began.
bool read_record(InputStream& in, std::vector<std::string>& fields, std::size_t& start_line, bool first) {
  std::string line;
  do {
    start_line = in.line();
    if (!in.getline(line)) return false;
    if (first && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);  // UTF-8 byte order mark
    first = false;
  } while (skippable(line));

  fields.clear();
  std::string field;
  bool quoted = false, in_quotes = false, after_quotes = false;
  std::size_t i = 0;
  auto finish = [&] {
    fields.push_back(quoted ? field : std::string(trim(field)));
    field.clear();
    quoted = after_quotes = false;
  };
  for (;;) {
    if (i == line.size()) {
      if (!in_quotes) break;
      std::string next;
      if (!in.getline(next)) throw InputError(fmt::format("{}:{}", in.name(), start_line), "quoted field never closed");
      line += '\n';
      line += next;
      continue;
    }
    const char c = line[i++];
    if (in_quotes) {
      if (c != '"') field += c;
      else if (i < line.size() && line[i] == '"') field += '"', ++i;
      else in_quotes = false, after_quotes = true;
    } else if (c == ',') {
      finish();
    } else if (after_quotes) {
      if (c != ' ' && c != '\t')
        throw InputError(fmt::format("{}:{}", in.name(), start_line), fmt::format("text after a closing quote in field {}", fields.size() + 1));
    } else if (c == '"' && trim(field).empty()) {
      field.clear();
      quoted = in_quotes = true;
    } else {
      field += c;
    }
  }
  finish();
  return true;
}

}  // namespace

CsvTable CsvTable::read(InputStream& in) {
  CsvTable t;
  t.name_ = in.name();
  std::vector<std::string> fields;
  std::size_t line = 0;
  if (!read_record(in, fields, line, true)) throw InputError(t.name_, "empty table: no header line");
  t.columns_ = fields;
  for (std::size_t i = 0; i < t.columns_.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (!t.columns_[i].empty() && t.columns_[i] == t.columns_[j])
        throw InputError(fmt::format("{}:{}", t.name_, line), fmt::format("column '{}' appears twice in the header", t.columns_[i]));
  while (read_record(in, fields, line, false)) {
    if (fields.size() != t.columns_.size())
      throw InputError(fmt::format("{}:{}", t.name_, line),
                       fmt::format("{} fields, the header has {}", fields.size(), t.columns_.size()));
    for (const std::string& f : fields) {
      t.text_ += f;
      t.cell_end_.push_back(t.text_.size());
    }
    t.line_of_row_.push_back(line);
  }
  return t;
}

CsvTable CsvTable::read(const std::string& path) {
  auto in = InputStream::open(path, "a CSV file");
  return read(*in);
}

std::optional<std::size_t> CsvTable::find_column(std::string_view column) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == column) return i;
  return std::nullopt;
}

std::size_t CsvTable::column(std::string_view column) const {
  if (auto i = find_column(column)) return *i;
  throw InputError(name_, fmt::format("no column '{}' (columns: {})", column, fmt::join(columns_, ", ")));
}

std::string CsvTable::where(std::size_t row) const { return fmt::format("{}:{}", name_, line_of(row)); }

InputError CsvTable::cell_error(std::size_t row, std::size_t col, std::string_view what) const {
  return InputError(where(row), fmt::format("column '{}': '{}' is not {}", columns_[col], text(row, col), what));
}

double CsvTable::number(std::size_t row, std::size_t col) const {
  std::string_view s = text(row, col);
  if (s.starts_with('+')) s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) throw cell_error(row, col, "a number");
  if (!std::isfinite(v)) throw cell_error(row, col, "a finite number");
  return v;
}

std::int64_t CsvTable::integer(std::size_t row, std::size_t col) const {
  std::string_view s = text(row, col);
  if (s.starts_with('+')) s.remove_prefix(1);
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) throw cell_error(row, col, "an integer");
  return v;
}

std::int64_t CsvTable::date(std::size_t row, std::size_t col) const {
  if (auto t = parse_iso_date(text(row, col))) return *t;
  throw cell_error(row, col, "a date (YYYY-MM-DD, YYYY-MM-DDThh:mm:ss or YYYYMMDD)");
}

std::vector<double> CsvTable::numbers(std::string_view name) const {
  const std::size_t col = column(name);
  std::vector<double> r(rows());
  for (std::size_t i = 0; i < rows(); ++i) r[i] = number(i, col);
  return r;
}

std::vector<std::int64_t> CsvTable::dates(std::string_view name) const {
  const std::size_t col = column(name);
  std::vector<std::int64_t> r(rows());
  for (std::size_t i = 0; i < rows(); ++i) r[i] = date(i, col);
  return r;
}

// ---- writing ----------------------------------------------------------------------------------

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns, std::span<const std::string> comments)
    : out_(path), ncolumns_(columns.size()) {
  if (columns.empty()) throw std::logic_error("csv writer: no columns");
  for (const std::string& c : comments) {
    std::string line = c;
    for (char& ch : line)
      if (ch == '\n' || ch == '\r') ch = ' ';
    buf_ += "# " + line + "\n";
  }
  for (const std::string& c : columns) text(c);
  end_row();
}

void CsvWriter::cell(std::string_view s) {
  if (in_row_ == ncolumns_) throw std::logic_error(fmt::format("csv writer: more than {} cells in a row", ncolumns_));
  if (in_row_++ > 0) buf_ += ',';
  buf_ += s;
}

CsvWriter& CsvWriter::text(std::string_view s) {
  const bool needs_quotes = s.find_first_of(",\"\n\r") != std::string_view::npos || s != trim(s) ||
                            (in_row_ == 0 && s.starts_with('#'));
  if (!needs_quotes) {
    cell(s);
    return *this;
  }
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  q += '"';
  cell(q);
  return *this;
}

CsvWriter& CsvWriter::number(double v) {
  cell(fmt::format("{}", v));
  return *this;
}

CsvWriter& CsvWriter::number(double v, int decimals) {
  cell(fmt::format("{:.{}f}", v, decimals));
  return *this;
}

CsvWriter& CsvWriter::integer(std::int64_t v) {
  cell(fmt::format("{}", v));
  return *this;
}

CsvWriter& CsvWriter::date(std::int64_t seconds) {
  cell(format_iso_date(seconds));
  return *this;
}

void CsvWriter::end_row() {
  if (in_row_ != ncolumns_)
    throw std::logic_error(fmt::format("csv writer: row has {} cells, the header {}", in_row_, ncolumns_));
  buf_ += '\n';
  in_row_ = 0;
  if (buf_.size() > (1 << 20)) {
    out_.write(buf_);
    buf_.clear();
  }
}

void CsvWriter::commit() {
  if (in_row_ != 0) throw std::logic_error("csv writer: commit in the middle of a row");
  out_.write(buf_);
  buf_.clear();
  out_.commit();
}

}  // namespace ugs
