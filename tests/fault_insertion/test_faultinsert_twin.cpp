// The sample twin end to end (small variant, data-samples/po-plain): generate.py --small,
// ugs-mesh2d with the fault traces as constraint lines, ugs-meshgen with the faults' depth ranges
// and dips (the six faults dip: they are cut into the mesh along their planes),
// then ugs-faultinsert --faults faults.geojson: the two regional and four local faults are inserted,
// the summary reports each, and the faulted mesh passes the structural checks and glues back.
#include <gtest/gtest.h>

#include <filesystem>

#include "fault_meshes.hpp"
#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"

namespace ugs::test {
namespace {

TEST(FaultInsertTwin, RegionalAndLocalFaultsOfTheSmallTwin) {
  const auto dir = temp_dir("faultinsert-twin");
  const std::string src = std::string(UGS_SOURCE_DIR) + "/data-samples/po-plain";
  ASSERT_EQ(run("/usr/bin/python3 " + src + "/generate.py --small --out " + dir.string() + " -q").exit_code, 0);
  const std::string cd = "cd " + dir.string() + " && ";
  auto r = run(cd + tool("ugs-mesh2d") +
               " --domain domain.geojson --refine refinement.geojson --trace reservoir_traces.geojson"
               " --fault faults.geojson --section sections.geojson -q -o plan.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run(cd + tool("ugs-meshgen") + " plan.msh --strata strata.toml -q -o model.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run(cd + "cat model.msh | " + tool("ugs-faultinsert") + " --faults faults.geojson > faulted.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const Mesh input = read_msh((dir / "model.msh").string());
  const Mesh out = read_msh((dir / "faulted.msh").string());
  const char* names[] = {"overthrust_north", "backthrust_south", "local_1", "local_2", "local_3", "local_4"};
  std::size_t elements = 0;
  for (const char* n : names) {
    const std::string g = std::string("fault:") + n;
    const ElementBlock* tri = find_block(input, 2, g, ElementType::Triangle);
    const ElementBlock* prism = find_block(out, 3, g, ElementType::Prism);
    ASSERT_NE(tri, nullptr) << n;
    ASSERT_NE(prism, nullptr) << n;
    EXPECT_EQ(prism->size(), tri->size()) << n;
    EXPECT_GT(prism->size(), 100u) << n;
    elements += prism->size();
    // Reported per fault, with its triangle count.
    const std::string count = std::to_string(tri->size());
    EXPECT_NE(r.err.find(std::string("ugs-faultinsert: ") + n), std::string::npos) << r.err;
  }
  EXPECT_NE(r.err.find("6 faults: "), std::string::npos) << r.err;
  // ugs-meshgen cut the dipping faults along their planes (docs/dipping-faults.md): the mesh's
  // groups agree with the traces, so no warning about their distance from the dipping surfaces.
  EXPECT_EQ(r.err.find("triangles are used; they"), std::string::npos) << r.err;
  EXPECT_EQ(out.count(ElementType::Prism), elements);
  EXPECT_GT(out.num_nodes(), input.num_nodes());
  check_faulted(out);
  expect_glues_back(out, input);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ugs::test
