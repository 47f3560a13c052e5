// The pressure change of a flow run on the unfaulted mesh (ugs-submesh cuts the flow sub-meshes from
// model.msh, before ugs-faultinsert) drives the faulted mesh: every element gets the mean of its
// corners' values in the flow file, and the twins ugs-faultinsert made get the value of the node they
// were split from, so both faces of a fault see the same fluid pressure.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "fault_meshes.hpp"
#include "pressure_files.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;

namespace {

double dp_of(const Point3& x) { return 1e5 + 200.0 * x[0] - 30.0 * x[1] + 75.0 * x[2]; }

CaseFile linear_case() {
  CaseFile c;
  c.path = "test.toml";
  c.materials.push_back(test::linear_material("rock", "test", 10e9, 0.25));
  c.faults.push_back(test::fault_spec("F", "test.toml:1", 0.0, 30));
  return c;
}

}  // namespace

TEST(PressureOnFaults, FlowFieldOfTheUnfaultedMeshDrivesTheFaultedOne) {
  BoxMeshSpec spec;
  spec.x = linspace(0, 1000, 10);
  spec.y = linspace(0, 500, 5);
  spec.z = linspace(-1000, 0, 10);
  const Mesh plain = make_box_mesh(spec);
  Mesh faulted = plain;
  test::add_planar_fault(faulted, "F", {500, 0, -500}, {1, 0, 0},
                         [](const Point3& c) { return c[2] > -800 && c[2] < -200; }, 1e-6);
  test::insert_all_faults(faulted);
  ASSERT_GT(faulted.num_nodes(), plain.num_nodes());

  // The flow file: the unfaulted mesh's tetrahedra, dp linear in space.
  const auto path = (std::filesystem::temp_directory_path() / "ugs-test-pressure-on-faults.h5").string();
  {
    FieldSeriesOptions o;
    o.cell_types = {ElementType::Tetrahedron};
    testcase::write_pressure(path, plain, {{"2000-01-01", "2001-01-01"}, [](const Point3& x, std::size_t) { return dp_of(x); }}, o);
  }

  const CaseFile cs = linear_case();
  const mech::Model model = mech::build_model(faulted, cs, true);
  mech::PressureHistory history({path}, faulted, model);
  EXPECT_EQ(history.forced_cells(), model.tets.size());

  const auto cell = history.cell_dp(978307200.0);
  for (std::size_t e = 0; e < model.tets.size(); ++e) {
    double mean = 0;
    for (auto n : model.tets[e]) mean += 0.25 * dp_of(faulted.nodes[n]);
    ASSERT_NEAR(cell[e], mean, 1e-9 * std::abs(mean)) << "element " << model.tet_tags[e];
  }
  // The turning-point scan's view: the same values, for the forced elements only.
  auto forced = history.forced_cell_dp(978307200.0);
  ASSERT_EQ(forced.size(), history.forced_cells());
  auto all = cell;
  std::sort(forced.begin(), forced.end());
  std::sort(all.begin(), all.end());
  EXPECT_EQ(forced, all);
  // Every node, twins included, carries the value at its position (linear field: exact).
  const auto node = history.node_dp(978307200.0);
  std::size_t twins = 0;
  for (std::size_t i = 0; i < faulted.num_nodes(); ++i) {
    ASSERT_NEAR(node[i], dp_of(faulted.nodes[i]), 1e-9 * std::abs(dp_of(faulted.nodes[i]))) << "node " << faulted.node_tags[i];
    twins += i >= plain.num_nodes();
  }
  EXPECT_GT(twins, 0u);
  std::filesystem::remove(path);
  std::filesystem::remove(std::filesystem::path(path).replace_extension(".xdmf"));
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
