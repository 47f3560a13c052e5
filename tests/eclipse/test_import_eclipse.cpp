// ugs-import-eclipse end to end: OPM Flow runs the tiny corner-point deck of make_deck.py (a
// faulted pillar, an inactive cell, MAPAXES, non-planar cells; METRIC unified restart and FIELD
// non-unified), the tool maps it onto a tetrahedral box mesh in map coordinates, and every
// tetrahedron's dp is checked against the restart's PRESSURE of its cell, read here directly with
// EclIO and located here from the deck's own formulas (not the tool's geometry code).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <opm/io/eclipse/EclFile.hpp>
#include <opm/io/eclipse/EclOutput.hpp>
#include <opm/io/eclipse/ERst.hpp>

#include "case_toml.hpp"
#include "pressure_files.hpp"
#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

// The deck's geometry, as make_deck.py writes it.
constexpr int NX = 8, NY = 6, NZ = 4;
constexpr double THROW = 15.0;
constexpr double OX = 600000.0, OY = 5000000.0, CX = 0.8, SX = 0.6;  // MAPAXES: X axis along (0.8, 0.6)
constexpr int INACTIVE_I = 2, INACTIVE_J = 2, INACTIVE_K = 1;         // 0-based (3,3,2)

double top(double i, double j) { return 1000.0 + 4.0 * i + 3.0 * j + 0.6 * i * j; }
double thickness(int k, int i, int j) { return 10.0 + 0.5 * std::sin(i + 2 * j + k); }
double horizon(int k, int i, int j, bool east) {
  double d = top(i, j);
  for (int m = 0; m < k; ++m) d += thickness(m, i, j);
  return d + (east ? THROW : 0.0);
}

Point3 to_map(double x, double y, double depth) { return {OX + x * CX - y * SX, OY + x * SX + y * CX, -depth}; }

// Where a map point lies in the deck: the cell (i, j, k) 0-based, or none; `sure` is false within
// 1 m of a cell boundary, where the tool's piecewise-planar faces and the bilinear ones differ.
struct Where {
  bool inside = false, sure = true;
  int i = -1, j = -1, k = -1;
};

Where locate_in_deck(const Point3& p) {
  const double dx = p[0] - OX, dy = p[1] - OY, depth = -p[2];
  const double x = dx * CX + dy * SX, y = -dx * SX + dy * CX;
  const double xi = (x - 2.0 * (depth - 900.0) / 300.0) / 100.0, eta = y / 100.0;  // pillars lean 2 m east per 300 m
  Where w;
  const double tol = 0.01;  // 1 m of 100 m
  if (xi < -tol || eta < -tol || xi > NX + tol || eta > NY + tol) return w;
  auto near_int = [&](double v) { return std::abs(v - std::round(v)) < tol; };
  if (near_int(xi) || near_int(eta) || xi < 0 || eta < 0 || xi > NX || eta > NY) w.sure = false;
  w.i = std::clamp(static_cast<int>(std::floor(xi)), 0, NX - 1);
  w.j = std::clamp(static_cast<int>(std::floor(eta)), 0, NY - 1);
  const double u = xi - w.i, v = eta - w.j;
  const bool east = w.i >= 4;
  auto h = [&](int k) {
    return (1 - u) * (1 - v) * horizon(k, w.i, w.j, east) + u * (1 - v) * horizon(k, w.i + 1, w.j, east) +
           (1 - u) * v * horizon(k, w.i, w.j + 1, east) + u * v * horizon(k, w.i + 1, w.j + 1, east);
  };
  for (int k = 0; k <= NZ; ++k)
    if (std::abs(depth - h(k)) < 1.0) w.sure = false;
  if (depth < h(0) || depth > h(NZ)) {
    w.k = depth < h(0) ? -1 : NZ;  // above or below the grid
    return w;
  }
  for (int k = 0; k < NZ; ++k)
    if (depth <= h(k + 1)) {
      w.k = k;
      break;
    }
  w.inside = w.k >= 0 && xi >= 0 && eta >= 0 && xi <= NX && eta <= NY && !(w.i == INACTIVE_I && w.j == INACTIVE_J && w.k == INACTIVE_K);
  return w;
}

double when_s(const char* date) { return static_cast<double>(*parse_iso_date(date)); }

int active_index(int i, int j, int k) {
  const int g = i + NX * (j + NY * k);
  const int gi = INACTIVE_I + NX * (INACTIVE_J + NY * INACTIVE_K);
  return g < gi ? g : (g == gi ? -1 : g - 1);
}

// A box mesh over the deck's plan (and 55-65 m beyond it), rotated into map coordinates.
Mesh deck_mesh() {
  BoxMeshSpec spec;
  spec.x = linspace(-55, 865, 23);  // no tetrahedron centroid exactly on the grid's outer faces
  spec.y = linspace(-55, 665, 18);
  spec.z = linspace(-1150, -990, 16);
  spec.material = [](const Point3& c) { return c[2] > -1030 ? std::string("cap") : std::string("reservoir"); };
  Mesh m = make_box_mesh(spec);
  for (auto& n : m.nodes) n = to_map(n[0], n[1], -n[2]);
  return m;
}

struct Tet {
  std::uint64_t tag;
  Point3 centroid;
};

std::vector<Tet> tets_of(const Mesh& m) {
  std::vector<Tet> out;
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (std::size_t e = 0; e < b.size(); ++e) {
        Point3 c{0, 0, 0};
        for (auto n : b.element(e))
          for (int d = 0; d < 3; ++d) c[d] += 0.25 * m.nodes[n][d];
        out.push_back({b.tags[e], c});
      }
  return out;
}

// PRESSURE per report step, read straight from the restart file(s) with EclIO.
std::vector<std::vector<float>> restart_pressures(const std::vector<std::string>& files, std::vector<std::string>* dates) {
  std::vector<std::vector<float>> p;
  for (const auto& f : files) {
    Opm::EclIO::ERst r(f);
    for (int s : r.listOfReportStepNumbers()) {
      r.loadReportStepNumber(s);
      p.push_back(r.getRestartData<float>("PRESSURE", s));
      const auto& ih = r.getRestartData<int>("INTEHEAD", s);
      if (dates) dates->push_back(fmt::format("{:04d}-{:02d}-{:02d}", ih[66], ih[65], ih[64]));
    }
  }
  return p;
}

class ImportEclipse : public ::testing::Test {
protected:
  // OPM Flow's output for the two decks, made once per build folder (ctest runs each test in its
  // own process): made in a temporary folder and renamed into place, remade when make_deck.py changes.
  static fs::path flow_runs() {
    const fs::path runs = fs::path(UGS_BINARY_DIR) / "tests" / "eclipse" / "flow-runs";
    const fs::path deck = fs::path(UGS_SOURCE_DIR) / "tests" / "eclipse" / "make_deck.py";
    if (fs::exists(runs / "done") && fs::last_write_time(runs / "done") >= fs::last_write_time(deck)) return runs;
    const fs::path tmp = runs.string() + ".tmp." + std::to_string(::getpid());
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    for (const auto& [name, args] : {std::pair<std::string, std::string>{"TINY", ""}, {"FTINY", "--units field --no-unifout"}}) {
      const auto r = test::run(fmt::format("cd {} && {} {} {}.DATA {} && {} {}.DATA --output-dir=. > {}.log 2>&1", tmp.string(),
                                           UGS_PYTHON, deck.string(), name, args, UGS_FLOW, name, name));
      if (r.exit_code != 0) {
        ADD_FAILURE() << name << ": " << r.err << test::slurp(tmp / (name + ".log"));
        return {};
      }
    }
    test::spit(tmp / "done", "");
    std::error_code ec;
    if (fs::exists(runs / "done") && fs::last_write_time(runs / "done") >= fs::last_write_time(deck)) {
      fs::remove_all(tmp);  // another test process made them meanwhile
      return runs;
    }
    fs::remove_all(runs, ec);
    fs::rename(tmp, runs, ec);
    if (ec) fs::remove_all(tmp);
    return runs;
  }
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::temp_dir("import-eclipse"));
    const fs::path runs = flow_runs();
    ASSERT_FALSE(runs.empty());
    for (const auto& e : fs::directory_iterator(runs))
      if (e.path().stem() == "TINY" || e.path().stem() == "FTINY") fs::copy_file(e.path(), *dir_ / e.path().filename());
    write_msh(deck_mesh(), (*dir_ / "mesh.msh").string(), MshEncoding::Binary);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static std::string path(const std::string& f) { return (*dir_ / f).string(); }
  static test::RunResult import(const std::string& args) {
    return test::run(test::tool("ugs-import-eclipse") + " " + args);
  }

  // Checks every tetrahedron of out.h5 against the restart, with `unit` Pa per restart unit.
  void check_against_restart(const std::string& h5, const std::vector<std::string>& restart_files, double unit,
                             std::size_t* located = nullptr) {
    std::vector<std::string> dates;
    const auto P = restart_pressures(restart_files, &dates);
    ASSERT_EQ(P.size(), 5u);
    EXPECT_EQ(dates, (std::vector<std::string>{"2020-01-01", "2020-01-31", "2020-03-01", "2020-03-31", "2020-04-30"}));
    FieldSeriesReader in(h5);
    ASSERT_EQ(in.steps().size(), P.size());
    for (std::size_t s = 0; s < P.size(); ++s) EXPECT_EQ(in.steps()[s].date, dates[s]);
    std::map<std::uint64_t, std::size_t> row;
    const auto tags = in.cell_tags();
    for (std::size_t c = 0; c < tags.size(); ++c) row[tags[c]] = c;
    std::vector<Field> dp;
    for (std::size_t s = 0; s < P.size(); ++s) dp.push_back(in.cell_field(s, "dp"));
    const Mesh mesh = read_msh(path("mesh.msh"));
    std::size_t checked = 0, absent = 0, in_inactive = 0, fault_east = 0, fault_west = 0, unsure = 0;
    for (const Tet& t : tets_of(mesh)) {
      const Where w = locate_in_deck(t.centroid);
      const auto it = row.find(t.tag);
      if (!w.sure) {
        ++unsure;
        // Near a boundary: any neighbour's pressure change (two layers up or down across the
        // faulted pillar, whose throw is 1.5 layers), or none.
        if (it == row.end()) continue;
        bool any = false;
        for (int di = -1; di <= 1 && !any; ++di)
          for (int dj = -1; dj <= 1 && !any; ++dj)
            for (int dk = -2; dk <= 2 && !any; ++dk) {
              const int i = w.i + di, j = w.j + dj, k = std::clamp(w.k, 0, NZ - 1) + dk;
              if (i < 0 || j < 0 || k < 0 || i >= NX || j >= NY || k >= NZ || active_index(i, j, k) < 0) continue;
              const int a = active_index(i, j, k);
              any = std::abs(dp[4].values[it->second] - (double(P[4][a]) * unit - double(P[0][a]) * unit)) < 1e-6;
            }
        EXPECT_TRUE(any) << "tetrahedron " << t.tag << " near a cell boundary has the pressure change of no neighbour";
        continue;
      }
      if (!w.inside) {
        EXPECT_EQ(it, row.end()) << "tetrahedron " << t.tag << " outside every active cell got a value";
        ++absent;
        if (w.i == INACTIVE_I && w.j == INACTIVE_J && w.k == INACTIVE_K) ++in_inactive;
        continue;
      }
      ASSERT_NE(it, row.end()) << "tetrahedron " << t.tag << " in cell " << w.i + 1 << "," << w.j + 1 << "," << w.k + 1 << " got no value";
      const int a = active_index(w.i, w.j, w.k);
      for (std::size_t s = 0; s < P.size(); ++s) {
        const double expected = double(P[s][a]) * unit - double(P[0][a]) * unit;
        ASSERT_NEAR(dp[s].values[it->second], expected, 1e-9 * std::abs(double(P[s][a]) * unit))
            << "tetrahedron " << t.tag << " cell " << w.i + 1 << "," << w.j + 1 << "," << w.k + 1 << " step " << s;
      }
      ++checked;
      if (w.i == 3) ++fault_west;
      if (w.i == 4) ++fault_east;
    }
    // The test means something: most tetrahedra checked exactly, on both sides of the faulted
    // pillar, some in the inactive cell and some outside the grid.
    EXPECT_GT(checked, 3000u);
    EXPECT_LT(unsure, checked);
    EXPECT_GT(fault_west, 100u);
    EXPECT_GT(fault_east, 100u);
    EXPECT_GT(in_inactive, 3u);
    EXPECT_GT(absent, 1000u);
    // The pressure changes: injection raises, production lowers it, in every checked cell.
    double lo = 0, hi = 0;
    for (double v : dp[2].values) hi = std::max(hi, v);
    for (double v : dp[4].values) lo = std::min(lo, v);
    EXPECT_GT(hi, 5e5);
    EXPECT_LT(lo, -5e5);
    for (double v : dp[0].values) EXPECT_EQ(v, 0.0);
    if (located) *located = tags.size();
  }

  static fs::path* dir_;
};
fs::path* ImportEclipse::dir_ = nullptr;

std::size_t count_lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

// Damaging a binary file by hand: the first array header named `name` (8 characters, blank-padded)
// starts 4 bytes before the name; its data's first record marker 24 bytes after that.
std::size_t header_at(const std::string& bytes, const std::string& name) {
  const auto p = bytes.find(name);
  EXPECT_NE(p, std::string::npos) << name;
  return p == std::string::npos ? 0 : p - 4;
}
void put_be32(std::string& bytes, std::size_t at, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int b = 0; b < 4; ++b) bytes[at + b] = static_cast<char>((u >> (24 - 8 * b)) & 0xff);
}

// The same arrays as a formatted file (CASE.FEGRID, CASE.FUNRST), written by EclIO.
void to_formatted(const std::string& from, const std::string& to) {
  Opm::EclIO::EclFile in(from);
  in.loadData();
  Opm::EclIO::EclOutput out(to, true);
  const auto list = in.getList();
  for (std::size_t n = 0; n < list.size(); ++n) {
    const auto& [name, type, count] = list[n];
    const int i = static_cast<int>(n);
    switch (type) {
      case Opm::EclIO::INTE: out.write(name, in.get<int>(i)); break;
      case Opm::EclIO::REAL: out.write(name, in.get<float>(i)); break;
      case Opm::EclIO::DOUB: out.write(name, in.get<double>(i)); break;
      case Opm::EclIO::LOGI: out.write(name, in.get<bool>(i)); break;
      case Opm::EclIO::CHAR: out.write(name, in.get<std::string>(i)); break;
      case Opm::EclIO::MESS: out.message(name); break;
      default: FAIL() << from << ": array " << name << " of a type this test does not convert";
    }
  }
}

}  // namespace

TEST_F(ImportEclipse, MetricUnifiedRestartMatchesPressureOfEveryCell) {
  const auto r = import(path("TINY.EGRID") + " --restart " + path("TINY.UNRST") + " --mesh " + path("mesh.msh") + " -o " +
                        path("metric.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t located = 0;
  check_against_restart(path("metric.h5"), {path("TINY.UNRST")}, 1e5, &located);
  // The count it reports is the tetrahedra it did not write.
  const std::size_t total = tets_of(read_msh(path("mesh.msh"))).size();
  EXPECT_NE(r.err.find(fmt::format("{} of {} tetrahedra in active cells; {} outside every active cell", located, total,
                                   total - located)),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("8 x 6 x 4 cells, 191 active, 30 NNCs, METRES, MAPAXES"), std::string::npos) << r.err;
}

TEST_F(ImportEclipse, FieldUnitsNonUnifiedRestart) {
  // Any of the numbered files names the series; the restart beside the EGRID is found without it.
  const auto r = import(path("FTINY.EGRID") + " --restart " + path("FTINY.X0002") + " --mesh " + path("mesh.msh") + " -o " +
                        path("field.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> files;
  for (int s = 0; s <= 4; ++s) files.push_back(path(fmt::format("FTINY.X{:04d}", s)));
  check_against_restart(path("field.h5"), files, 6894.757293168361);
  EXPECT_NE(r.err.find("FEET, MAPAXES"), std::string::npos) << r.err;
  // The same reservoir in feet and psia: the same pressure change as the METRIC run, to the
  // simulator's convergence.
  const auto m = import(path("TINY.EGRID") + " --mesh " + path("mesh.msh") + " -o " + path("metric2.h5"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  FieldSeriesReader a(path("metric2.h5")), b(path("field.h5"));
  // Corner points in feet with 4 decimals, in float32: a tetrahedron whose centroid is within a
  // few 0.1 mm of a face may change sides; the others are the same.
  std::map<std::uint64_t, std::size_t> rb;
  const auto ta = a.cell_tags(), tb = b.cell_tags();
  for (std::size_t c = 0; c < tb.size(); ++c) rb[tb[c]] = c;
  const auto da = a.cell_field(2, "dp").values, db = b.cell_field(2, "dp").values;
  double amax = 0, diff = 0;
  std::size_t common = 0;
  for (std::size_t c = 0; c < ta.size(); ++c) {
    const auto it = rb.find(ta[c]);
    if (it == rb.end()) continue;
    ++common;
    amax = std::max(amax, std::abs(da[c]));
    diff = std::max(diff, std::abs(da[c] - db[it->second]));
  }
  EXPECT_GT(common, ta.size() - 20);
  EXPECT_GT(common, tb.size() - 20);
  EXPECT_GT(amax, 5e5);
  EXPECT_LT(diff, 0.01 * amax);
}

TEST_F(ImportEclipse, OffsetShiftsTheGrid) {
  // The grid shifted 100 km east misses the mesh: exit 2, one line with both extents, no output.
  const auto out = path("off.h5");
  const auto r = import(path("TINY.EGRID") + " --mesh " + path("mesh.msh") + " --offset 100000,0,0 -o " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex("^ugs-import-eclipse: error: .*TINY.EGRID: the grid \\(x 69[0-9.]+\\.\\..*\\) does not "
                                                   "overlap the mesh .*mesh.msh \\(tetrahedron centroids x 59[0-9.]+\\.\\.")))
      << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(path("off.xdmf")));
  // 200 m deeper, it misses the mesh too.
  const auto s = import(path("TINY.EGRID") + " --mesh " + path("mesh.msh") + " --offset 0,0,-200 -o " + out);
  EXPECT_EQ(s.exit_code, 2) << s.err;
}

TEST_F(ImportEclipse, BadInputExitsTwoWithOneLineAndNoOutput) {
  const auto out = path("bad.h5");
  auto expect_bad = [&](const std::string& args, const std::string& fragment) {
    const auto r = import(args + " --mesh " + path("mesh.msh") + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("ugs-import-eclipse: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << r.err;
    EXPECT_FALSE(fs::exists(out));
    for (const auto& e : fs::directory_iterator(*dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  };
  expect_bad(path("MISSING.EGRID"), "MISSING.EGRID: no such file");
  expect_bad(path("TINY.EGRID") + " --restart " + path("MISSING.UNRST"), "MISSING.UNRST: no such file");
  // Truncated files: EclIO's std::runtime_error becomes the one line.
  const std::string egrid = test::slurp(path("TINY.EGRID")), unrst = test::slurp(path("TINY.UNRST"));
  test::spit(path("CUT.EGRID"), egrid.substr(0, egrid.size() / 2));
  expect_bad(path("CUT.EGRID") + " --restart " + path("TINY.UNRST"), "CUT.EGRID: cannot be read as ECLIPSE binary output");
  test::spit(path("CUT.UNRST"), unrst.substr(0, unrst.size() - 100));
  expect_bad(path("TINY.EGRID") + " --restart " + path("CUT.UNRST"), "CUT.UNRST: cannot be read as ECLIPSE binary output");
  // The restart of another grid (the FIELD run has the same grid: same counts, so it is accepted).
  {
    Opm::EclIO::EclOutput w(path("OTHER.UNRST"), false);
    std::vector<int> ih(411, 0);
    ih[2] = 1, ih[8] = 8, ih[9] = 6, ih[10] = 4, ih[11] = 192, ih[64] = 1, ih[65] = 1, ih[66] = 2020;
    w.write<int>("SEQNUM", {0});
    w.write<int>("INTEHEAD", ih);
    w.write<float>("PRESSURE", std::vector<float>(192, 100.0f));
  }
  expect_bad(path("TINY.EGRID") + " --restart " + path("OTHER.UNRST"),
             "OTHER.UNRST: report step 0: PRESSURE has 192 values, but " + path("TINY.EGRID") + " has 191 active cells");
  {
    Opm::EclIO::EclOutput w(path("NOP.UNRST"), false);
    std::vector<int> ih(411, 0);
    ih[2] = 1, ih[8] = 8, ih[9] = 6, ih[10] = 4, ih[11] = 191, ih[64] = 1, ih[65] = 1, ih[66] = 2020;
    w.write<int>("SEQNUM", {0});
    w.write<int>("INTEHEAD", ih);
    w.write<float>("SWAT", std::vector<float>(191, 0.5f));
  }
  expect_bad(path("TINY.EGRID") + " --restart " + path("NOP.UNRST"), "NOP.UNRST: report step 0: no PRESSURE array");
  {
    Opm::EclIO::EclOutput w(path("UNITS.UNRST"), false);
    std::vector<int> ih(411, 0);
    ih[2] = 7, ih[8] = 8, ih[9] = 6, ih[10] = 4, ih[11] = 191, ih[64] = 1, ih[65] = 1, ih[66] = 2020;
    w.write<int>("SEQNUM", {0});
    w.write<int>("INTEHEAD", ih);
    w.write<float>("PRESSURE", std::vector<float>(191, 100.0f));
  }
  expect_bad(path("TINY.EGRID") + " --restart " + path("UNITS.UNRST"),
             "UNITS.UNRST: report step 0: INTEHEAD item 3: unit system 7 in INTEHEAD item 3 (expected 1 METRIC, 2 FIELD, 3 LAB or 4 PVT-M)");
  expect_bad(path("TINY.EGRID") + " --offset 1,2", "--offset");
}

TEST_F(ImportEclipse, FormattedFilesGiveTheSamePressureChange) {
  to_formatted(path("TINY.EGRID"), path("TINY.FEGRID"));
  to_formatted(path("TINY.UNRST"), path("TINY.FUNRST"));
  const auto r = import(path("TINY.FEGRID") + " --restart " + path("TINY.FUNRST") + " --mesh " + path("mesh.msh") + " -o " +
                        path("formatted.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  check_against_restart(path("formatted.h5"), {path("TINY.FUNRST")}, 1e5);
  EXPECT_NE(r.err.find("8 x 6 x 4 cells, 191 active, 30 NNCs, METRES, MAPAXES"), std::string::npos) << r.err;
}

// Damaged files that EclIO itself would crash on, fill the memory with, or throw from where the
// tool did not expect it: each is refused by the record walk or the check of EGrid's arrays
// (formats/eclipse/src/records.hpp, eclipse.cpp) with one line, exit 2, no output.
TEST_F(ImportEclipse, DamagedFilesAreRefusedBeforeEclioReadsThem) {
  const auto out = path("damaged.h5");
  const auto expect_refused = [&](const std::string& egrid, const std::string& restart, const std::string& fragment) {
    const auto r = import(path(egrid) + " --restart " + path(restart) + " --mesh " + path("mesh.msh") + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << egrid << " " << restart << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("ugs-import-eclipse: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << r.err;
    for (const char c : r.err) EXPECT_TRUE(c == '\n' || std::isprint(static_cast<unsigned char>(c))) << r.err;
    EXPECT_FALSE(fs::exists(out));
  };
  const std::string egrid = test::slurp(path("TINY.EGRID")), unrst = test::slurp(path("TINY.UNRST"));
  {
    // NNCHEAD naming local grid 3 of none: EGrid's constructor indexed its list of LGR names (SIGSEGV).
    std::string b = egrid;
    put_be32(b, header_at(b, "NNCHEAD ") + 24 + 4 + 4, 3);
    test::spit(path("LGR.EGRID"), b);
    expect_refused("LGR.EGRID", "TINY.UNRST", "LGR.EGRID: NNCHEAD (array number 10) names local grid 3, but 0 are defined before it");
  }
  {
    // ACTNUM's header renamed COORD: EGrid took the second COORD (192 items) for the pillars.
    std::string b = egrid;
    b.replace(header_at(b, "ACTNUM  ") + 4, 8, "COORD   ");
    test::spit(path("COORD2.EGRID"), b);
    expect_refused("COORD2.EGRID", "TINY.UNRST", "COORD2.EGRID: a second COORD array in the global grid (array number 8)");
  }
  {
    // An unknown type of non-printable bytes: the line says '?' for them.
    std::string b = egrid;
    b.replace(header_at(b, "ZCORN   ") + 16, 4, "\xa0\xa1XY");
    test::spit(path("TYPE.EGRID"), b);
    expect_refused("TYPE.EGRID", "TINY.UNRST", "TYPE.EGRID: cannot be read as ECLIPSE binary output: byte");
    expect_refused("TYPE.EGRID", "TINY.UNRST", "array ZCORN: unknown type '??XY'");
  }
  {
    // The second step's PRESSURE record marker off by 400 bytes, mid-file: EclIO's exception came
    // from a load outside the tool's guard ("internal error", exit 1).
    std::string b = unrst;
    const auto first = b.find("PRESSURE");
    const auto second = b.find("PRESSURE", first + 8) - 4;
    put_be32(b, second + 24, 191 * 4 - 400);
    test::spit(path("MARK.UNRST"), b);
    expect_refused("TINY.EGRID", "MARK.UNRST",
                   fmt::format("MARK.UNRST: cannot be read as ECLIPSE binary output: byte {}: array PRESSURE (191 items): record of 364 "
                               "bytes ends with the marker",
                               second + 24));
  }
  {
    // A formatted header's count of 2^31 - 1: EclIO allocated 23 GB for the text (killed by the OOM killer).
    to_formatted(path("TINY.EGRID"), path("BIG.FEGRID"));
    to_formatted(path("TINY.UNRST"), path("BIG.FUNRST"));
    std::string t = test::slurp(path("BIG.FUNRST"));
    const auto h = t.find("'PRESSURE'");
    ASSERT_NE(h, std::string::npos);
    const auto eol = t.find('\n', h);
    t.replace(h, eol - h, "'PRESSURE'  2147483647 'REAL'");
    test::spit(path("BIG.FUNRST"), t);
    expect_refused("BIG.FEGRID", "BIG.FUNRST", "BIG.FUNRST: cannot be read as ECLIPSE formatted output: byte");
    expect_refused("BIG.FEGRID", "BIG.FUNRST", "array PRESSURE: 2147483647 items, more than the file's");
    t.replace(h, t.find('\n', h) - h, "'PRESSURE'       20000 'REAL'");
    test::spit(path("BIG.FUNRST"), t);
    expect_refused("BIG.FEGRID", "BIG.FUNRST", "array PRESSURE: 20000 items take 345000 bytes, but");
    // Strings of 99 characters: EclIO's formatted reader divides by 80 / (99 + 3) = 0 (SIGFPE).
    std::string g = test::slurp(path("BIG.FEGRID"));
    const auto c = g.find("'CHAR'");
    ASSERT_NE(c, std::string::npos);
    g.replace(c, 6, "'C099'");
    test::spit(path("C99.FEGRID"), g);
    expect_refused("C99.FEGRID", "TINY.UNRST", "strings of 99 characters (type C099; expected 1 to 77)");
  }
}

TEST_F(ImportEclipse, CaseKeepsThePoolMaterialsOnly) {
  test::spit(*dir_ / "s.csv", "date,p_MPa\n2020-01-01,10\n");
  test::spit(*dir_ / "case.toml",
             "[[material]]\nname = \"cap\"\nnu = 0.3\n[[material]]\nname = \"reservoir\"\nnu = 0.3\n"
             "[[pool]]\nname = \"P\"\nmaterials = [\"reservoir\"]\nschedule = \"s.csv\"\ncolumn = \"p_MPa\"\n");
  const auto r = import(path("TINY.EGRID") + " --mesh " + path("mesh.msh") + " --case " + path("case.toml") + " -o " + path("case.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh mesh = read_msh(path("mesh.msh"));
  std::size_t cap = 0;
  std::map<std::uint64_t, double> z;
  for (const Tet& t : tets_of(mesh)) {
    z[t.tag] = t.centroid[2];
    cap += t.centroid[2] > -1030;
  }
  EXPECT_NE(r.err.find(fmt::format("; {} not of the case's pool materials", cap)), std::string::npos) << r.err;
  FieldSeriesReader in(path("case.h5"));
  EXPECT_GT(in.cell_tags().size(), 1000u);
  for (const auto tag : in.cell_tags()) EXPECT_LT(z.at(tag), -1030) << tag;
}

TEST_F(ImportEclipse, ExportsStrainAndStressChangePerCellAsGrdecl) {
  // Mechanics results on the test mesh: uniform strain and stress changes, different per date.
  const Mesh mesh = read_msh(path("mesh.msh"));
  {
    FieldSeriesWriter w(path("solve.h5"), mesh);
    const std::size_t n = w.cell_count();
    auto uniform = [&](const char* name, std::array<double, 3> d) {
      Field f{name, 6, std::vector<double>(6 * n, 0.0)};
      for (std::size_t c = 0; c < n; ++c)
        for (int k = 0; k < 3; ++k) f.values[6 * c + k] = d[k];
      return f;
    };
    const std::vector<Field> a{uniform("strain", {1e-4, 2e-4, 3e-4}), uniform("stress_change", {-1e5, -2e5, -3e5})};
    const std::vector<Field> b{uniform("strain", {-1e-4, -1e-4, -1e-4}), uniform("stress_change", {1.5e5, 1.5e5, 1.5e5})};
    w.add_step("2020-01-31", when_s("2020-01-31"), {}, a);
    w.add_step("2020-04-30", when_s("2020-04-30"), {}, b);
    w.commit();
  }
  const auto r = import(path("TINY.EGRID") + " --export " + path("solve.h5") + " -o " + path("mech.grdecl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Parse the GRDECL: keywords, values with N*value runs, '/' ends a keyword.
  std::map<std::string, std::vector<double>> kw;
  {
    std::istringstream in(test::slurp(path("mech.grdecl")));
    std::string line, current;
    while (std::getline(in, line)) {
      if (line.rfind("--", 0) == 0 || line.empty()) continue;
      if (current.empty()) {
        current = line;
        continue;
      }
      std::istringstream ls(line);
      std::string tok;
      while (ls >> tok) {
        if (tok == "/") {
          current.clear();
          break;
        }
        const auto star = tok.find('*');
        if (star == std::string::npos) {
          kw[current].push_back(std::stod(tok));
        } else {
          for (int k = 0; k < std::stoi(tok.substr(0, star)); ++k) kw[current].push_back(std::stod(tok.substr(star + 1)));
        }
      }
    }
  }
  ASSERT_EQ(kw.size(), 4u);
  const std::map<std::string, double> expected{{"UGSEV1", 6e-4}, {"UGSDSM1", -2.0}, {"UGSEV2", -3e-4}, {"UGSDSM2", 1.5}};
  std::set<int> sure_cells;
  for (const Tet& t : tets_of(mesh)) {
    const Where w = locate_in_deck(t.centroid);
    if (w.sure && w.inside) sure_cells.insert(w.i + NX * (w.j + NY * w.k));
  }
  EXPECT_GT(sure_cells.size(), 150u);
  for (const auto& [name, value] : expected) {
    ASSERT_EQ(kw[name].size(), 192u) << name;
    EXPECT_EQ(kw[name][INACTIVE_I + NX * (INACTIVE_J + NY * INACTIVE_K)], 0.0) << name;
    for (const int g : sure_cells) EXPECT_NEAR(kw[name][g], value, 1e-6 * std::abs(value)) << name << " cell " << g;
  }
  // An unknown date: exit 2, one line naming the steps there are, nothing written.
  const auto bad = import(path("TINY.EGRID") + " --export " + path("solve.h5") + " --dates 2020-02-01 -o " + path("bad.grdecl"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_EQ(count_lines(bad.err), 1u) << bad.err;
  EXPECT_NE(bad.err.find("2020-02-01"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("bad.grdecl")));
}

TEST_F(ImportEclipse, SolveTakesTheImportedPressureAndItWinsOverANodeField) {
  // The two commands of docs/eclipse.md: import, then ugs-solve. A ugs-flow-like node field of zero
  // over the whole mesh given too changes nothing where the simulator's cell field is (its
  // elements keep the simulator's pressure), and adds zero elsewhere: the same displacements.
  ASSERT_EQ(import(path("TINY.EGRID") + " --mesh " + path("mesh.msh") + " -o " + path("sim.h5")).exit_code, 0);
  const Mesh mesh = read_msh(path("mesh.msh"));
  testcase::write_pressure(path("zero.h5"), mesh, testcase::uniform_series({"2020-01-01", "2020-04-30"}, {0.0, 0.0}));
  test::spit(*dir_ / "solve.toml", testcase::CaseToml("", testcase::Numbers::Plain, testcase::Layout::Compact)
                                       .initial_stress({.surface_elevation_m = 0, .k0 = 0.9})
                                       .material(testcase::elastic("cap", 0.3))
                                       .material(testcase::elastic("reservoir", 0.3))
                                       .str());
  const std::string solve = test::tool("ugs-solve") + " " + path("mesh.msh") + " --case " + path("solve.toml");
  const auto a = test::run(solve + " --pressure " + path("sim.h5") + " -o " + path("a.h5"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b = test::run(solve + " --pressure " + path("zero.h5") + " --pressure " + path("sim.h5") + " -o " + path("b.h5"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  FieldSeriesReader ra(path("a.h5")), rb(path("b.h5"));
  ASSERT_EQ(ra.steps().size(), 5u);
  ASSERT_EQ(rb.steps().size(), 5u);
  double up_injection = 0, up_production = 0;
  for (std::size_t s = 0; s < 5; ++s) {
    const auto ua = ra.node_field(s, "u").values, ub = rb.node_field(s, "u").values;
    ASSERT_EQ(ua.size(), ub.size());
    for (std::size_t i = 0; i < ua.size(); ++i) ASSERT_NEAR(ua[i], ub[i], 1e-12 + 1e-9 * std::abs(ua[i])) << "step " << s;
    for (std::size_t i = 2; i < ua.size(); i += 3) {
      if (s == 2) up_injection = std::max(up_injection, ua[i]);
      if (s == 4) up_production = std::min(up_production, ua[i]);
    }
  }
  // Injection (+1.45 MPa at most) lifts, production below the start (-1.0 MPa) lowers the grid.
  EXPECT_GT(up_injection, 0.0);
  EXPECT_LT(up_production, 0.0);
}
