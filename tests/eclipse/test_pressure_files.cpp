// ugs-solve --pressure with a simulator's cell field and ugs-flow's node field together
// (docs/eclipse.md): the cell field `dp` acts on its elements as it is, the node field is averaged
// over the element's nodes; where both cover an element the cell field wins whatever the order of
// the files; two files of the same kind on one element are refused.
#include <gtest/gtest.h>

#include <cmath>

#include "pressure_files.hpp"
#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/mechanics/pressure.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

mech::Model model_of(const Mesh& m) {
  mech::Model model;
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (std::size_t e = 0; e < b.size(); ++e) {
        const auto n = b.element(e);
        model.tets.push_back({n[0], n[1], n[2], n[3]});
        model.tet_tags.push_back(b.tags[e]);
      }
  model.x = m.nodes;
  model.fixed.assign(m.num_nodes(), 0);
  return model;
}

// The sub-mesh of the tetrahedra with tags in `keep` (parent tags kept), as ugs-import-eclipse writes.
Mesh sub_mesh(const Mesh& m, const std::set<std::uint64_t>& keep) {
  Mesh s;
  s.physicals = m.physicals;
  s.entities = m.entities;
  std::vector<std::int64_t> nn(m.num_nodes(), -1);
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    ElementBlock out{b.entity_dim, b.entity_tag, b.type, {}, {}};
    for (std::size_t e = 0; e < b.size(); ++e) {
      if (!keep.count(b.tags[e])) continue;
      out.tags.push_back(b.tags[e]);
      for (auto n : b.element(e)) {
        if (nn[n] < 0) {
          nn[n] = static_cast<std::int64_t>(s.nodes.size());
          s.nodes.push_back(m.nodes[n]);
          s.node_tags.push_back(m.node_tags[n]);
        }
        out.nodes.push_back(static_cast<std::uint32_t>(nn[n]));
      }
    }
    s.blocks.push_back(out);
  }
  return s;
}

double when(const char* date) { return static_cast<double>(*parse_iso_date(date)); }

class PressureFiles : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = test::temp_dir("pressure-files");
    mesh_ = test::unit_cube_mesh();
    model_ = model_of(mesh_);
    ASSERT_EQ(model_.tets.size(), 6u);
    // ugs-flow: +1 MPa at every node on 2020-03-01.
    testcase::write_pressure(dir_ / "flow.h5", mesh_, testcase::uniform_series({"2020-01-01", "2020-03-01"}, {0.0, 1e6}));
    // The simulator: the first three tetrahedra, -2, -4, -6 MPa.
    write_cells("sim.h5", {model_.tet_tags[0], model_.tet_tags[1], model_.tet_tags[2]});
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write_cells(const std::string& name, const std::set<std::uint64_t>& tags) {
    const Mesh s = sub_mesh(mesh_, tags);
    FieldSeriesOptions o;
    o.cell_types = {ElementType::Tetrahedron};
    FieldSeriesWriter w((dir_ / name).string(), s, o);
    Field zero{"dp", 1, std::vector<double>(w.cell_count(), 0.0)}, down = zero;
    for (std::size_t c = 0; c < down.values.size(); ++c) down.values[c] = -2e6 * static_cast<double>(c + 1);
    w.add_step("2020-01-01", when("2020-01-01"), {}, std::span<const Field>(&zero, 1));
    w.add_step("2020-03-01", when("2020-03-01"), {}, std::span<const Field>(&down, 1));
    w.commit();
  }
  std::string path(const std::string& f) const { return (dir_ / f).string(); }

  fs::path dir_;
  Mesh mesh_;
  mech::Model model_;
};

}  // namespace

TEST_F(PressureFiles, CellFieldWinsOverNodeFieldInEitherOrder) {
  for (const auto& files : {std::vector<std::string>{path("flow.h5"), path("sim.h5")}, {path("sim.h5"), path("flow.h5")}}) {
    mech::PressureHistory h(files, mesh_, model_);
    EXPECT_EQ(h.forced_cells(), 6u);
    const auto dp = h.cell_dp(when("2020-03-01"));
    EXPECT_EQ(dp, (std::vector<double>{-2e6, -4e6, -6e6, 1e6, 1e6, 1e6}));
    // Linear in time: 2020-01-31 is 30 of the 60 days.
    const auto half = h.cell_dp(when("2020-01-31"));
    EXPECT_DOUBLE_EQ(half[1], -2e6);
    EXPECT_DOUBLE_EQ(half[4], 0.5e6);
    // Nodal output: a node of a simulator cell takes the mean of those cells, the others ugs-flow's.
    const auto nd = h.node_dp(when("2020-03-01"));
    for (std::uint32_t n = 0; n < mesh_.num_nodes(); ++n) {
      double sum = 0;
      int cells = 0;
      for (int e = 0; e < 3; ++e)
        for (int k = 0; k < 4; ++k)
          if (model_.tets[e][k] == n) sum += dp[e], ++cells;
      EXPECT_DOUBLE_EQ(nd[n], cells ? sum / cells : 1e6) << "node " << n;
    }
  }
}

TEST_F(PressureFiles, CellFieldAlone) {
  mech::PressureHistory h({path("sim.h5")}, mesh_, model_);
  EXPECT_EQ(h.forced_cells(), 3u);
  EXPECT_EQ(h.cell_dp(when("2020-03-01")), (std::vector<double>{-2e6, -4e6, -6e6, 0, 0, 0}));
  EXPECT_EQ(h.forced_cell_dp(when("2020-03-01")), (std::vector<double>{-2e6, -4e6, -6e6}));
  // Held after its last date, zero before its first.
  EXPECT_EQ(h.cell_dp(when("2020-06-01"))[2], -6e6);
  EXPECT_EQ(h.cell_dp(when("2019-06-01"))[2], 0.0);
}

TEST_F(PressureFiles, TwoCellFieldsOnOneElementAreRefused) {
  write_cells("sim2.h5", {model_.tet_tags[2], model_.tet_tags[3]});
  try {
    mech::PressureHistory h({path("sim.h5"), path("sim2.h5")}, mesh_, model_);
    FAIL() << "overlap accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path("sim2.h5") + ": element " + std::to_string(model_.tet_tags[2]) +
                                         " is also under the pressure of " + path("sim.h5") +
                                         ": two cell fields (or two node fields) must not overlap; a cell field takes "
                                         "precedence over a node field only");
  }
}

// A cell tag twice in one file: the element would silently take the later entry's pressure.
TEST_F(PressureFiles, CellTagTwiceInOneFileIsRefused) {
  Mesh s = sub_mesh(mesh_, {model_.tet_tags[0], model_.tet_tags[1]});
  ASSERT_EQ(s.blocks.size(), 1u);
  ASSERT_EQ(s.blocks[0].tags.size(), 2u);
  s.blocks[0].tags[1] = s.blocks[0].tags[0];
  {
    FieldSeriesOptions o;
    o.cell_types = {ElementType::Tetrahedron};
    FieldSeriesWriter w(path("twice.h5"), s, o);
    const Field zero{"dp", 1, std::vector<double>(w.cell_count(), 0.0)};
    w.add_step("2020-01-01", when("2020-01-01"), {}, std::span<const Field>(&zero, 1));
    w.commit();
  }
  try {
    mech::PressureHistory h({path("twice.h5")}, mesh_, model_);
    FAIL() << "a cell tag twice accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path("twice.h5") + ": /mesh/cell_tags: cell tag " + std::to_string(model_.tet_tags[0]) +
                                         " appears twice (entries 0 and 1)");
  }
}
