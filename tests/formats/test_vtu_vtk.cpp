// Our hand-written .vtu and .pvd files, read back by VTK's own XML reader and parser: same point
// count, coordinates, cell types, connectivity and bit-identical field values.
#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "sample_fields.hpp"
#include "ugs/formats/vtu.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

constexpr int kVtkTriangle = 5, kVtkTetra = 10, kVtkWedge = 13;

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const fs::path& p) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(p.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0) << p;
  vtkSmartPointer<vtkUnstructuredGrid> g = reader->GetOutput();
  return g;
}

void expect_array(vtkDataArray* a, const Field& f) {
  ASSERT_NE(a, nullptr) << f.name;
  EXPECT_EQ(a->GetDataType(), VTK_DOUBLE) << f.name;
  ASSERT_EQ(a->GetNumberOfComponents(), f.components) << f.name;
  ASSERT_EQ(static_cast<std::size_t>(a->GetNumberOfTuples()), f.count()) << f.name;
  for (std::size_t i = 0; i < f.count(); ++i)
    for (int k = 0; k < f.components; ++k)
      ASSERT_EQ(a->GetComponent(i, k), f.values[i * f.components + k]) << f.name << " tuple " << i;
}

// The cells VTK read, as (type, node ids) in file order.
std::vector<std::pair<int, std::vector<vtkIdType>>> cells_of(vtkUnstructuredGrid* g) {
  std::vector<std::pair<int, std::vector<vtkIdType>>> r;
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    vtkIdType n;
    const vtkIdType* ids;
    g->GetCellPoints(c, n, ids);
    r.emplace_back(g->GetCellType(c), std::vector<vtkIdType>(ids, ids + n));
  }
  return r;
}

}  // namespace

TEST(VtuVtk, VolumeWithInterfacePrismAndFields) {
  const auto dir = test::temp_dir("vtu-volume");
  const Mesh m = test::faulted_cube_mesh();
  const std::vector<Field> point_fields = {test::sample_field("dp", 1, m.num_nodes(), 0, 0.5),
                                           test::sample_field("u", 3, m.num_nodes(), 0, -2.0)};
  const std::size_t ncells = output_cell_count(m, default_output_cell_types(m));
  ASSERT_EQ(ncells, 7u);  // 6 tets then the prism; the top triangles are left out by default
  const std::vector<Field> cell_fields = {test::sample_field("stress", 6, ncells, 0, 3.25),
                                          test::sample_field("chi", 1, ncells, 0, 0.125)};
  write_vtu(m, (dir / "cube.vtu").string(), point_fields, cell_fields);

  auto g = read_vtu(dir / "cube.vtu");
  ASSERT_EQ(static_cast<std::size_t>(g->GetNumberOfPoints()), m.num_nodes());
  for (vtkIdType i = 0; i < g->GetNumberOfPoints(); ++i) {
    double x[3];
    g->GetPoint(i, x);
    EXPECT_EQ(x[0], m.nodes[i][0]);
    EXPECT_EQ(x[1], m.nodes[i][1]);
    EXPECT_EQ(x[2], m.nodes[i][2]);
  }
  EXPECT_EQ(g->GetPoints()->GetDataType(), VTK_DOUBLE);

  const auto cells = cells_of(g);
  ASSERT_EQ(cells.size(), ncells);
  std::size_t c = 0;
  for (const ElementBlock& b : m.blocks) {
    if (b.type == ElementType::Triangle) continue;
    for (std::size_t i = 0; i < b.size(); ++i, ++c) {
      EXPECT_EQ(cells[c].first, b.type == ElementType::Tetrahedron ? kVtkTetra : kVtkWedge);
      const auto nodes = b.element(i);
      EXPECT_EQ(cells[c].second, std::vector<vtkIdType>(nodes.begin(), nodes.end()));
    }
  }

  for (const Field& f : point_fields) expect_array(g->GetPointData()->GetArray(f.name.c_str()), f);
  for (const Field& f : cell_fields) expect_array(g->GetCellData()->GetArray(f.name.c_str()), f);

  vtkDataArray* tags = g->GetPointData()->GetArray("node_tag");
  ASSERT_NE(tags, nullptr);
  EXPECT_EQ(tags->GetDataType(), VTK_TYPE_INT64);
  for (std::size_t i = 0; i < m.num_nodes(); ++i) EXPECT_EQ(tags->GetComponent(i, 0), double(m.node_tags[i]));

  vtkDataArray* material = g->GetCellData()->GetArray("material");
  vtkDataArray* etags = g->GetCellData()->GetArray("element_tag");
  ASSERT_NE(material, nullptr);
  ASSERT_NE(etags, nullptr);
  EXPECT_EQ(material->GetDataType(), VTK_TYPE_INT32);
  const int rock = m.find_physical(3, "mat:rock")->tag, fault = m.find_physical(3, "fault:F1")->tag;
  for (int i = 0; i < 6; ++i) EXPECT_EQ(material->GetComponent(i, 0), rock);
  EXPECT_EQ(material->GetComponent(6, 0), fault);
  EXPECT_EQ(etags->GetComponent(6, 0), double(m.count(ElementType::Tetrahedron) + m.count(ElementType::Triangle) + 1));
  fs::remove_all(dir);
}

TEST(VtuVtk, ChosenTypesAndSurfaceDefault) {
  const auto dir = test::temp_dir("vtu-types");
  const Mesh m = test::faulted_cube_mesh();
  write_vtu(m, (dir / "top.vtu").string(), {}, {}, VtuOptions{{ElementType::Triangle}});
  auto top = read_vtu(dir / "top.vtu");
  ASSERT_EQ(top->GetNumberOfCells(), 2);
  EXPECT_EQ(top->GetCellType(0), kVtkTriangle);
  EXPECT_EQ(top->GetCellType(1), kVtkTriangle);

  write_vtu(m, (dir / "fault.vtu").string(), {}, {}, VtuOptions{{ElementType::Prism}});
  auto fault = read_vtu(dir / "fault.vtu");
  ASSERT_EQ(fault->GetNumberOfCells(), 1);
  EXPECT_EQ(fault->GetCellType(0), kVtkWedge);

  // A plan mesh without 3D cells is written as its triangles.
  Mesh plan;
  for (int i = 0; i < 4; ++i) plan.add_node({double(i % 2), double(i / 2), 0.0});
  const std::uint32_t t[2][3] = {{0, 1, 3}, {0, 3, 2}};
  auto& b = plan.block(2, plan.entity_for_physical(2, "plan"), ElementType::Triangle);
  for (const auto& tri : t) plan.add_element(b, tri);
  write_vtu(plan, (dir / "plan.vtu").string());
  auto g = read_vtu(dir / "plan.vtu");
  ASSERT_EQ(g->GetNumberOfCells(), 2);
  EXPECT_EQ(g->GetCellType(1), kVtkTriangle);
  fs::remove_all(dir);
}

// Arrays spanning several compression blocks, including one of exactly whole blocks (the
// header's last-block size is then 0) must decompress to the same values.
TEST(VtuVtk, ArraysOfSeveralCompressionBlocks) {
  const auto dir = test::temp_dir("vtu-large");
  Mesh m;
  const std::size_t n = 131072;  // 1 MiB of doubles per component: whole blocks
  for (std::size_t i = 0; i < n; ++i) m.add_node({i * 0.5, std::sin(double(i)), -1.0 * i}, 1000 + 3 * i);
  auto& b = m.block(3, m.entity_for_physical(3, "mat:rock"), ElementType::Tetrahedron);
  for (std::uint32_t i = 0; i + 3 < 4000; ++i) {
    const std::uint32_t t[4] = {i, i + 1, i + 2, i + 3};
    m.add_element(b, t);
  }
  const std::vector<Field> fields = {test::sample_field("p", 1, n, 0, 1.0), test::sample_field("u", 3, n + 0, 0, 2.0),
                                     test::sample_field("w", 5, n, 0, 3.0)};
  write_vtu(m, (dir / "large.vtu").string(), fields);
  auto g = read_vtu(dir / "large.vtu");
  ASSERT_EQ(static_cast<std::size_t>(g->GetNumberOfPoints()), n);
  ASSERT_EQ(g->GetNumberOfCells(), 3997);
  for (const Field& f : fields) expect_array(g->GetPointData()->GetArray(f.name.c_str()), f);
  vtkDataArray* tags = g->GetPointData()->GetArray("node_tag");
  EXPECT_EQ(tags->GetComponent(n - 1, 0), double(1000 + 3 * (n - 1)));
  double x[3];
  g->GetPoint(n - 1, x);
  EXPECT_EQ(x[1], std::sin(double(n - 1)));
  fs::remove_all(dir);
}

TEST(VtuVtk, PvdListsTheSeries) {
  const auto dir = test::temp_dir("vtu-pvd");
  const Mesh m = test::faulted_cube_mesh();
  PvdWriter pvd((dir / "series.pvd").string());
  const double times[] = {0.0, 86400.0 * 365.25, 1.5e9};
  for (int s = 0; s < 3; ++s) {
    const std::vector<Field> pf = {test::sample_field("dp", 1, m.num_nodes(), s, 0.0)};
    const std::string name = "series_" + std::to_string(s) + ".vtu";
    write_vtu(m, (dir / name).string(), pf);
    pvd.add(times[s], name);
  }
  EXPECT_FALSE(fs::exists(dir / "series.pvd"));  // nothing before commit
  pvd.commit();

  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName((dir / "series.pvd").c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement* root = parser->GetRootElement();
  ASSERT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* coll = root->GetNestedElement(0);
  ASSERT_STREQ(coll->GetName(), "Collection");
  ASSERT_EQ(coll->GetNumberOfNestedElements(), 3);
  for (int s = 0; s < 3; ++s) {
    vtkXMLDataElement* ds = coll->GetNestedElement(s);
    double t = -1;
    ASSERT_TRUE(ds->GetScalarAttribute("timestep", t));
    EXPECT_EQ(t, times[s]);
    auto g = read_vtu(dir / ds->GetAttribute("file"));
    expect_array(g->GetPointData()->GetArray("dp"), test::sample_field("dp", 1, m.num_nodes(), s, 0.0));
  }
  fs::remove_all(dir);
}

TEST(VtuVtk, MismatchedFieldLeavesNoFile) {
  const auto dir = test::temp_dir("vtu-bad");
  const Mesh m = test::faulted_cube_mesh();
  const std::vector<Field> bad = {test::sample_field("dp", 1, m.num_nodes() - 1, 0, 0.0)};
  EXPECT_THROW(write_vtu(m, (dir / "bad.vtu").string(), bad), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_THROW(write_vtu(m, (dir / "missing" / "x.vtu").string()), InputError);
  fs::remove_all(dir);
}
