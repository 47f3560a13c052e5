// The structural checks of test_fault_insert on the thesis-scale benchmark case (bench/faultinsert:
// 498,525 nodes, 2,878,848 tetrahedra, six crossing faults, 26,496 interface elements): every twin
// glues back to the input, each side is a face of one tetrahedron on its side, no tetrahedron
// holds both sides. Long (tens of seconds): label bench-long.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "fault_meshes.hpp"
#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/fault_insert.hpp"

namespace ugs::test {
namespace {

TEST(FaultThesisScale, ChecksHoldOnTheBenchmarkCase) {
  const auto dir = temp_dir("fault-thesis-scale");
  const std::string gen = std::string(UGS_BINARY_DIR) + "/bench/make_faultinsert_bench " + dir.string();
  ASSERT_EQ(run(gen).exit_code, 0);
  const Mesh input = read_msh((dir / "groups.msh").string());
  Mesh m = input;
  const auto r = insert_faults(m);
  std::size_t triangles = 0;
  for (const auto& f : r.faults) triangles += f.triangles;
  EXPECT_EQ(triangles, 26496u);
  EXPECT_EQ(r.new_nodes, 13128u);
  check_faulted(m);
  expect_glues_back(m, input);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ugs::test
