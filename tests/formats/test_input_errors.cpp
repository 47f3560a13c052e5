// Issue 20: every reader of formats/ refuses a directory, a missing file and a file of another kind
// with ONE line naming the file (the exception's text is the whole message) and prints nothing of
// its own on stderr (HDF5's automatic error stack is silenced wherever HDF5 files are opened).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "run_tool.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/formats/toml_reader.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

// The InputError message of `read`, checked to be one line with nothing else printed on stderr.
std::string one_line_error(const std::function<void()>& read) {
  std::string msg = "no error";
  testing::internal::CaptureStderr();
  try {
    read();
  } catch (const InputError& e) {
    msg = e.what();
  } catch (const std::exception& e) {
    msg = std::string("other exception: ") + e.what();
  }
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed, "") << "printed on stderr by the library";
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  return msg;
}

class InputErrors : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = test::temp_dir("input-errors");
    fs::create_directory(dir_ / "adir");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string p(const std::string& f) const { return (dir_ / f).string(); }
  fs::path dir_;
};

}  // namespace

TEST_F(InputErrors, DirectoryIsNamedForEveryKind) {
  const std::string d = p("adir");
  EXPECT_EQ(one_line_error([&] { read_msh(d); }), d + ": is a directory (expected an MSH file)");
  EXPECT_EQ(one_line_error([&] { CsvTable::read(d); }), d + ": is a directory (expected a CSV file)");
  EXPECT_EQ(one_line_error([&] { TomlTable::parse_file(d); }), d + ": is a directory (expected a TOML file)");
  EXPECT_EQ(one_line_error([&] { read_case_file(d); }), d + ": is a directory (expected a TOML file)");
  EXPECT_EQ(one_line_error([&] { FieldSeriesReader r(d); }), d + ": is a directory (expected an HDF5 file)");
}

TEST_F(InputErrors, MissingFileSaysWhy) {
  const std::string m = p("missing.h5");
  EXPECT_EQ(one_line_error([&] { FieldSeriesReader r(m); }), m + ": cannot open: No such file or directory");
  EXPECT_EQ(one_line_error([&] { read_msh(p("missing.msh")); }), p("missing.msh") + ": cannot open: No such file or directory");
  EXPECT_EQ(one_line_error([&] { TomlTable::parse_file(p("missing.toml")); }),
            p("missing.toml") + ": cannot open: No such file or directory");
}

TEST_F(InputErrors, NotHdf5AndTruncatedHdf5AreOneLine) {
  test::spit(dir_ / "text.h5", "date,p\n2015-01-01,1\n");
  EXPECT_EQ(one_line_error([&] { FieldSeriesReader r(p("text.h5")); }), p("text.h5") + ": not an HDF5 file");
  // A real field series cut in half: HDF5 fails deep inside; still one line, nothing printed.
  {
    Mesh m = test::unit_cube_mesh();
    FieldSeriesWriter w(p("full.h5"), m);
    w.add_step("2015-01-01", 0.0, std::vector<Field>{{"dp", 1, std::vector<double>(m.num_nodes(), 1.0)}}, {});
    w.commit();
  }
  const std::string full = test::slurp(dir_ / "full.h5");
  test::spit(dir_ / "cut.h5", full.substr(0, full.size() / 2));
  const std::string e = one_line_error([&] {
    FieldSeriesReader r(p("cut.h5"));
    for (std::size_t s = 0; s < r.steps().size(); ++s) r.node_field(s, "dp");
  });
  EXPECT_EQ(e.rfind(p("cut.h5") + ": ", 0), 0u) << e;
}

// TOML text that is not UTF-8 is one line naming line and column before toml11 parses it (toml11
// 3.7.1 read out of bounds on a literal string or quoted key holding such bytes): the case file
// and the stratigraphy go through TomlTable::parse_file like every TOML input.
TEST_F(InputErrors, TomlThatIsNotUtf8IsOneLine) {
  for (const std::string text : {"a = '\x9d'\n", "[model]\nname = '''x\n\xc0\xaf'''\n", "['\xed\xa0\x80']\nk = 1\n",
                                 "# \xf4\x90\x80\x80\n"}) {
    test::spit(p("bad.toml"), text);
    const std::string msg = one_line_error([&] { TomlTable::parse_file(p("bad.toml")); });
    EXPECT_NE(msg.find("is not UTF-8 (expected a UTF-8 text file)"), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind(p("bad.toml") + ":", 0), 0u) << msg;
    EXPECT_EQ(one_line_error([&] { read_case_file(p("bad.toml")); }), msg);
  }
  test::spit(p("bad.toml"), "[model]\nname = '''x\n\xc0\xaf'''\n");
  EXPECT_EQ(one_line_error([&] { TomlTable::parse_file(p("bad.toml")); }),
            p("bad.toml") + ":3: byte 0xc0 at column 1 is not UTF-8 (expected a UTF-8 text file)");
  // UTF-8 of every length is read.
  test::spit(p("good.toml"), "name = 'Po \xc3\xa0 \xe2\x82\xac \xf0\x9f\x8c\x8d'\n");
  EXPECT_EQ(TomlTable::parse_file(p("good.toml")).string("name"), "Po \xc3\xa0 \xe2\x82\xac \xf0\x9f\x8c\x8d");
}
