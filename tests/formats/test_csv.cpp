// CSV tables and ISO 8601 dates: parsing with quotes and comments, typed access, errors that
// name the file, line and column, dates before 1970 and across leap years, and the writer.
#include <gtest/gtest.h>

#include <functional>

#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

CsvTable parse(std::string text, std::string name = "t.csv") {
  auto in = InputStream::from_string(std::move(text), std::move(name));
  return CsvTable::read(*in);
}


}  // namespace

TEST(Dates, CivilDaysRoundTrip) {
  EXPECT_EQ(days_from_civil(1970, 1, 1), 0);
  EXPECT_EQ(days_from_civil(2000, 3, 1), 11017);
  EXPECT_EQ(days_from_civil(1969, 12, 31), -1);
  EXPECT_EQ(days_from_civil(1964, 1, 1), -2192);
  for (std::int64_t d = -800000; d <= 800000; d += 97) {
    const CivilDate c = civil_from_days(d);
    ASSERT_EQ(days_from_civil(c.year, c.month, c.day), d);
  }
}

TEST(Dates, ParseAndFormat) {
  EXPECT_EQ(parse_iso_date("1970-01-01"), 0);
  EXPECT_EQ(parse_iso_date("19700102"), 86400);
  EXPECT_EQ(parse_iso_date("2015-12-31T12:30:15"), 1451565015);
  EXPECT_EQ(parse_iso_date("2015-12-31 12:30:15Z"), 1451565015);
  EXPECT_EQ(parse_iso_date("2015-12-31T12:30"), 1451565000);
  EXPECT_EQ(parse_iso_date("1964-01-01"), -2192 * 86400);
  EXPECT_EQ(parse_iso_date("2000-02-29"), 951782400);
  for (const char* bad : {"", "2001-02-29", "1900-02-29", "2015-13-01", "2015-00-10", "2015-1-1", "2015-01-01T24:00:00",
                          "2015-01-01T10:60", "2015/01/01", "20150101T", "2015-01-01x", "1e5", " 2015-01-01"})
    EXPECT_FALSE(parse_iso_date(bad)) << bad;

  EXPECT_EQ(format_iso_date(0), "1970-01-01");
  EXPECT_EQ(format_iso_date(-1), "1969-12-31T23:59:59");
  EXPECT_EQ(format_iso_date(1451565015), "2015-12-31T12:30:15");
  for (const char* s : {"1964-01-01", "2024-02-29", "1999-12-31T23:59:59", "1900-03-01T00:00:01"})
    EXPECT_EQ(format_iso_date(*parse_iso_date(s)), s);
}

TEST(CsvRead, QuotesCommentsAndTrimming) {
  const CsvTable t = parse(
      "\xEF\xBB\xBF# pool A schedule\n"
      "date, p_MPa ,\"note, free\"\r\n"
      "\n"
      "1964-01-01,  -0.5 , \"plain\"\n"
      "# a comment between rows\n"
      "19650101,+1e-3,\"says \"\"hi\"\", twice\"\n"
      "1966-01-01T06:00:00,2,\"two\n"
      "lines\"\n"
      "1967-01-01,3,  \n");
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"date", "p_MPa", "note, free"}));
  ASSERT_EQ(t.rows(), 4u);
  const std::size_t p = t.column("p_MPa");
  EXPECT_EQ(t.number(0, p), -0.5);
  EXPECT_EQ(t.number(1, p), 1e-3);
  EXPECT_EQ(t.text(0, 2), "plain");
  EXPECT_EQ(t.text(1, 2), "says \"hi\", twice");
  EXPECT_EQ(t.text(2, 2), "two\nlines");
  EXPECT_EQ(t.text(3, 2), "");
  EXPECT_EQ(t.line_of(0), 4u);
  EXPECT_EQ(t.line_of(1), 6u);
  EXPECT_EQ(t.line_of(3), 9u);
  EXPECT_EQ(t.dates("date"),
            (std::vector<std::int64_t>{-2192 * 86400, -1826 * 86400, -1461 * 86400 + 6 * 3600, -1096 * 86400}));
  EXPECT_EQ(t.numbers("p_MPa"), (std::vector<double>{-0.5, 1e-3, 2, 3}));
  EXPECT_FALSE(t.find_column("q"));
}

TEST(CsvRead, ErrorsNameFileLineAndColumn) {
  const CsvTable t = parse("date,p_MPa,id\n2000-01-01,1.5,7\n2000-02-01,abc,x\n2000-03-01,nan,\n2000-13-01,1e999,3\n");
  EXPECT_EQ(test::input_error_of([&] { t.number(1, 1); }), "t.csv:3: column 'p_MPa': 'abc' is not a number");
  EXPECT_EQ(test::input_error_of([&] { t.number(2, 1); }), "t.csv:4: column 'p_MPa': 'nan' is not a finite number");
  EXPECT_EQ(test::input_error_of([&] { t.number(3, 1); }), "t.csv:5: column 'p_MPa': '1e999' is not a number");
  EXPECT_EQ(test::input_error_of([&] { t.number(2, 2); }), "t.csv:4: column 'id': '' is not a number");
  EXPECT_EQ(test::input_error_of([&] { t.integer(1, 2); }), "t.csv:3: column 'id': 'x' is not an integer");
  EXPECT_EQ(t.integer(0, 2), 7);
  EXPECT_EQ(test::input_error_of([&] { t.dates("date"); }),
            "t.csv:5: column 'date': '2000-13-01' is not a date (YYYY-MM-DD, YYYY-MM-DDThh:mm:ss or YYYYMMDD)");
  EXPECT_EQ(test::input_error_of([&] { t.column("q_m3"); }), "t.csv: no column 'q_m3' (columns: date, p_MPa, id)");
  EXPECT_EQ(test::input_error_of([&] { t.numbers("p_MPa"); }), "t.csv:3: column 'p_MPa': 'abc' is not a number");

  EXPECT_EQ(test::input_error_of([] { parse(""); }), "t.csv: empty table: no header line");
  EXPECT_EQ(test::input_error_of([] { parse("# only a comment\n\n"); }), "t.csv: empty table: no header line");
  EXPECT_EQ(test::input_error_of([] { parse("a,b\n1,2\n3\n"); }), "t.csv:3: 1 fields, the header has 2");
  EXPECT_EQ(test::input_error_of([] { parse("a,b\n1,2,\n"); }), "t.csv:2: 3 fields, the header has 2");
  EXPECT_EQ(test::input_error_of([] { parse("a,b,a\n"); }), "t.csv:1: column 'a' appears twice in the header");
  EXPECT_EQ(test::input_error_of([] { parse("a,b\n1,\"open\n2,3\n"); }), "t.csv:2: quoted field never closed");
  EXPECT_EQ(test::input_error_of([] { parse("a,b\n\"x\"y,2\n"); }), "t.csv:2: text after a closing quote in field 1");
}

TEST(CsvRead, FromFileAndPipe) {
  const auto dir = test::temp_dir("csv-read");
  test::spit(dir / "s.csv", "date,p_MPa\n2000-01-01,1\n2000-02-01,2\n");
  const CsvTable t = CsvTable::read((dir / "s.csv").string());
  EXPECT_EQ(t.name(), (dir / "s.csv").string());
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_EQ(test::input_error_of([&] { CsvTable::read((dir / "none.csv").string()); }),
            (dir / "none.csv").string() + ": cannot open: No such file or directory");

  // Through a real pipe on stdin (never seeks): a child process reads it back.
  const std::string cmd = "cat " + (dir / "s.csv").string() + " | " + std::string(UGS_CSV_PIPE_READER);
  const auto r = test::run(cmd);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "2 rows, p_MPa sum 3\n");
  fs::remove_all(dir);
}

TEST(CsvWrite, RoundTripThroughTheReader) {
  const auto dir = test::temp_dir("csv-write");
  const std::string path = (dir / "out.csv").string();
  {
    const std::vector<std::string> comments = {"written by test_csv", "second\nline"};
    CsvWriter w(path, {"date", "name", "uz_mm", "x_m", "id"}, comments);
    w.date(*parse_iso_date("1964-01-01")).text("A016VJP").number(-1.23456, 3).number(0.1).integer(-42).end_row();
    w.date(*parse_iso_date("2015-06-01T12:00:00")).text("with, comma \"q\"").number(2.0, 3).number(1.0 / 3.0).integer(7).end_row();
    EXPECT_THROW(w.text("short").end_row(), std::logic_error);
    EXPECT_FALSE(fs::exists(path));  // nothing before commit
    w.number(1).number(2).number(3).number(4).end_row();
    w.commit();
  }
  EXPECT_EQ(test::slurp(path),
            "# written by test_csv\n"
            "# second line\n"
            "date,name,uz_mm,x_m,id\n"
            "1964-01-01,A016VJP,-1.235,0.1,-42\n"
            "2015-06-01T12:00:00,\"with, comma \"\"q\"\"\",2.000,0.3333333333333333,7\n"
            "short,1,2,3,4\n");
  const CsvTable t = CsvTable::read(path);
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.text(1, 1), "with, comma \"q\"");
  EXPECT_EQ(t.number(1, 3), 1.0 / 3.0);  // shortest text reads back exactly
  EXPECT_EQ(t.date(1, 0), *parse_iso_date("2015-06-01T12:00:00"));
  fs::remove_all(dir);
}

TEST(CsvWrite, AbandonedWriterLeavesNothing) {
  const auto dir = test::temp_dir("csv-abandon");
  {
    CsvWriter w((dir / "x.csv").string(), {"a"});
    w.integer(1).end_row();
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}
