// HDF5 + XDMF field series, built once per HDF5 flavour (test_fields_serial, test_fields_mpi):
// writer -> reader round trips are exact, the reference XDMF library (libxdmf, the one behind
// ParaView's XDMF 3 reader) opens the index and finds the same grids, topologies and values,
// and bad files give one clear InputError.
#include <Xdmf.hpp>
#include <XdmfAttribute.hpp>
#include <XdmfAttributeCenter.hpp>
#include <XdmfDomain.hpp>
#include <XdmfGeometry.hpp>
#include <XdmfGridCollection.hpp>
#include <XdmfGridCollectionType.hpp>
#include <XdmfReader.hpp>
#include <XdmfTime.hpp>
#include <XdmfTopology.hpp>
#include <XdmfTopologyType.hpp>
#include <XdmfUnstructuredGrid.hpp>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstring>
#include <functional>
#include <limits>

#include <fmt/format.h>

#include "input_error.hpp"
#include "sample_fields.hpp"
#include "ugs/formats/fields.hpp"

namespace fs = std::filesystem;
using namespace ugs;

// FieldsSerial or FieldsMpi, so each flavour's tests have their own names in ctest.
#ifndef UGS_FIELDS_SUITE
#error "UGS_FIELDS_SUITE must name the HDF5 flavour's test suite"
#endif

namespace {

const char* kDates[] = {"1964-01-01", "1990-06-30", "2015-12-31T12:00:00"};
const double kTimes[] = {0.0, 8.5e8, 1.6251e9};

struct Series {
  std::vector<std::vector<Field>> node, cell;  // per step
};

// Writes three steps of a scalar and a vector node field and a tensor and scalar cell field.
Series write_series(const fs::path& h5, const Mesh& m, const FieldSeriesOptions& options = {}) {
  FieldSeriesWriter w(h5.string(), m, options);
  Series s;
  for (int k = 0; k < 3; ++k) {
    s.node.push_back({test::sample_field("dp", 1, m.num_nodes(), k, 0.25), test::sample_field("u", 3, m.num_nodes(), k, -7.0)});
    s.cell.push_back({test::sample_field("stress", 6, w.cell_count(), k, 11.0), test::sample_field("chi", 1, w.cell_count(), k, 0.1)});
    w.add_step(kDates[k], kTimes[k], s.node.back(), s.cell.back());
  }
  w.commit();
  return s;
}

// The XDMF indexes of the series `a`.h5 and `b`.h5 in `dir` are the same but for the file's name.
void expect_same_index(const fs::path& dir, const std::string& a, const std::string& b) {
  std::string xa = test::slurp(dir / (a + ".xdmf"));
  const std::string xb = test::slurp(dir / (b + ".xdmf"));
  for (std::size_t at = xa.find(a + ".h5:"); at != std::string::npos; at = xa.find(a + ".h5:", at)) xa.replace(at, a.size(), b);
  xa.replace(xa.find("Name=\"" + a + "\""), a.size() + 7, "Name=\"" + b + "\"");
  EXPECT_EQ(xa, xb);
}

void expect_same(const Field& a, const Field& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.components, b.components) << a.name;
  EXPECT_EQ(a.values, b.values) << a.name;  // bit-exact
}

std::vector<std::uint32_t> connectivity(const Mesh& m, ElementType t) {
  std::vector<std::uint32_t> r;
  for (const ElementBlock& b : m.blocks)
    if (b.type == t) r.insert(r.end(), b.nodes.begin(), b.nodes.end());
  return r;
}


// Overwrites value `i` of a dataset in place, as a damaged or hand-made file would hold it.
template <class T>
void poke_dataset(const std::string& file, const char* name, hid_t mem, std::size_t i, T value) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  ASSERT_GE(d, 0) << name;
  const hid_t space = H5Dget_space(d);
  std::vector<T> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  ASSERT_GE(H5Dread(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  v.at(i) = value;
  ASSERT_GE(H5Dwrite(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

shared_ptr<XdmfDomain> read_xdmf(const fs::path& p) {
  shared_ptr<XdmfReader> reader = XdmfReader::New();
  return shared_dynamic_cast<XdmfDomain>(reader->read(p.string()));
}

// Attribute values through libxdmf's own HDF5 reading.
void expect_xdmf_attribute(const shared_ptr<XdmfUnstructuredGrid>& g, const Field& f,
                           const shared_ptr<const XdmfAttributeCenter>& center) {
  shared_ptr<XdmfAttribute> a = g->getAttribute(f.name);
  ASSERT_TRUE(a) << f.name;
  EXPECT_EQ(a->getCenter(), center) << f.name;
  if (!a->isInitialized()) a->read();
  ASSERT_EQ(a->getSize(), f.values.size()) << f.name;
  for (unsigned i = 0; i < a->getSize(); ++i) ASSERT_EQ(a->getValue<double>(i), f.values[i]) << f.name << " " << i;
}

}  // namespace

TEST(UGS_FIELDS_SUITE, RoundTripIsExact) {
  const auto dir = test::temp_dir("fields-rt");
  const Mesh m = test::faulted_cube_mesh();
  const Series s = write_series(dir / "r.h5", m);
  EXPECT_TRUE(fs::exists(dir / "r.xdmf"));

  FieldSeriesReader r((dir / "r.h5").string());
  ASSERT_EQ(r.steps().size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(r.steps()[k].date, kDates[k]);
    EXPECT_EQ(r.steps()[k].time, kTimes[k]);
  }
  EXPECT_EQ(r.step("1990-06-30"), 1u);
  EXPECT_EQ(r.node_tags(), m.node_tags);
  EXPECT_EQ(r.coordinates(), m.nodes);
  EXPECT_EQ(r.cell_types(), (std::vector<ElementType>{ElementType::Tetrahedron, ElementType::Prism}));
  EXPECT_EQ(r.num_cells(), 7u);
  EXPECT_EQ(r.cells(ElementType::Tetrahedron), connectivity(m, ElementType::Tetrahedron));
  EXPECT_EQ(r.cells(ElementType::Prism), connectivity(m, ElementType::Prism));
  EXPECT_TRUE(r.cells(ElementType::Triangle).empty());
  EXPECT_EQ(r.cell_tags(), (std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 9}));
  const std::int32_t rock = m.find_physical(3, "mat:rock")->tag, fault = m.find_physical(3, "fault:F1")->tag;
  EXPECT_EQ(r.materials(), (std::vector<std::int32_t>{rock, rock, rock, rock, rock, rock, fault}));
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(r.node_field_names(k), (std::vector<std::string>{"dp", "u"}));
    EXPECT_EQ(r.cell_field_names(k), (std::vector<std::string>{"chi", "stress"}));
    for (const Field& f : s.node[k]) expect_same(r.node_field(k, f.name), f);
    for (const Field& f : s.cell[k]) expect_same(r.cell_field(k, f.name), f);
  }
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, XdmfLibraryReadsTheIndex) {
  const auto dir = test::temp_dir("fields-xdmf");
  const Mesh m = test::faulted_cube_mesh();
  const Series s = write_series(dir / "r.h5", m);

  shared_ptr<XdmfDomain> domain = read_xdmf(dir / "r.xdmf");
  ASSERT_TRUE(domain);
  ASSERT_EQ(domain->getNumberGridCollections(), 1u);
  shared_ptr<XdmfGridCollection> series = domain->getGridCollection(0);
  EXPECT_EQ(series->getType(), XdmfGridCollectionType::Temporal());
  ASSERT_EQ(series->getNumberUnstructuredGrids(), 3u);
  for (unsigned k = 0; k < 3; ++k) {
    shared_ptr<XdmfUnstructuredGrid> g = series->getUnstructuredGrid(k);
    EXPECT_EQ(g->getName(), kDates[k]);
    ASSERT_TRUE(g->getTime());
    EXPECT_EQ(g->getTime()->getValue(), kTimes[k]);
    EXPECT_EQ(g->getTopology()->getType(), XdmfTopologyType::Mixed());
    g->getTopology()->read();  // libxdmf counts mixed cells from the connectivity
    EXPECT_EQ(g->getTopology()->getNumberElements(), 7u);
    EXPECT_EQ(g->getGeometry()->getNumberPoints(), m.num_nodes());
    for (const Field& f : s.node[k]) expect_xdmf_attribute(g, f, XdmfAttributeCenter::Node());
    for (const Field& f : s.cell[k]) expect_xdmf_attribute(g, f, XdmfAttributeCenter::Cell());
  }

  // Geometry, node tags and the mixed topology also come through libxdmf's HDF5 reading.
  shared_ptr<XdmfUnstructuredGrid> g = series->getUnstructuredGrid(2);
  shared_ptr<XdmfGeometry> geo = g->getGeometry();
  if (!geo->isInitialized()) geo->read();
  for (std::size_t i = 0; i < m.num_nodes(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(geo->getValue<double>(3 * i + c), m.nodes[i][c]);
  shared_ptr<XdmfAttribute> tags = g->getAttribute("node_tag");
  ASSERT_TRUE(tags);
  tags->read();
  for (std::size_t i = 0; i < m.num_nodes(); ++i) EXPECT_EQ(tags->getValue<long long>(i), (long long)m.node_tags[i]);
  shared_ptr<XdmfTopology> topo = g->getTopology();
  ASSERT_EQ(topo->getSize(), 6u * 5 + 7);  // each cell: type code and its nodes
  EXPECT_EQ(topo->getValue<unsigned>(0), 6u);   // tetrahedron
  EXPECT_EQ(topo->getValue<unsigned>(30), 8u);  // wedge
  for (int k = 0; k < 6; ++k) EXPECT_EQ(topo->getValue<unsigned>(31 + k), m.blocks.back().nodes[k]);
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, SingleTypeTopologies) {
  const auto dir = test::temp_dir("fields-types");
  const Mesh m = test::faulted_cube_mesh();
  const struct {
    ElementType type;
    shared_ptr<const XdmfTopologyType> xdmf;
    unsigned cells;
  } cases[] = {{ElementType::Tetrahedron, XdmfTopologyType::Tetrahedron(), 6},
               {ElementType::Triangle, XdmfTopologyType::Triangle(), 2},
               {ElementType::Prism, XdmfTopologyType::Wedge(), 1}};
  for (const auto& c : cases) {
    const std::string name = std::string(element_name(c.type)).substr(0, 3) + ".h5";
    const Series s = write_series(dir / name, m, FieldSeriesOptions{{c.type}});
    FieldSeriesReader r((dir / name).string());
    EXPECT_EQ(r.num_cells(), c.cells);
    expect_same(r.cell_field(1, "chi"), s.cell[1][1]);

    auto domain = read_xdmf(dir / fs::path(name).replace_extension(".xdmf"));
    auto g = domain->getGridCollection(0)->getUnstructuredGrid(1);
    EXPECT_EQ(g->getTopology()->getType(), c.xdmf) << name;
    EXPECT_EQ(g->getTopology()->getNumberElements(), c.cells) << name;
    auto topo = g->getTopology();
    topo->read();
    const auto conn = connectivity(m, c.type);
    ASSERT_EQ(topo->getSize(), conn.size());
    for (unsigned i = 0; i < conn.size(); ++i) EXPECT_EQ(topo->getValue<unsigned>(i), conn[i]);
    expect_xdmf_attribute(g, s.cell[1][0], XdmfAttributeCenter::Cell());
  }
  fs::remove_all(dir);
}

namespace {

// A cloud of `n` nodes on a line with one tetrahedron: node fields of several chunks.
Mesh many_node_mesh(std::size_t n) {
  Mesh m;
  for (std::size_t i = 0; i < n; ++i) m.add_node({static_cast<double>(i), (i % 3) * 1.0, (i % 5) * 1.0}, i + 1);
  const std::uint32_t tet[4] = {0, 1, 3, 6};
  m.add_element(m.block(3, m.entity_for_physical(3, "mat:rock"), ElementType::Tetrahedron), tet);
  m.update_entity_bboxes();
  return m;
}

// HDF5's bytes of stored (deflated) data of a dataset.
hsize_t storage_size(const fs::path& h5, const std::string& dataset) {
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  const hsize_t n = H5Dget_storage_size(d);
  H5Dclose(d);
  H5Fclose(f);
  return n;
}

// Adds a chunked dataset with no chunk written to a committed file (replacing one of that name), as
// a damaged file could have it.
void add_unwritten_dataset(const std::string& h5, const char* name, std::vector<hsize_t> dims, hid_t type) {
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  if (H5Lexists(f, name, H5P_DEFAULT) > 0) {
    ASSERT_GE(H5Ldelete(f, name, H5P_DEFAULT), 0);
  }
  std::vector<hsize_t> chunk = dims;
  chunk[0] = std::min<hsize_t>(dims[0], 1024);
  const int rank = static_cast<int>(dims.size());
  const hid_t space = H5Screate_simple(rank, dims.data(), nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, rank, chunk.data());
  const hid_t d = H5Dcreate2(f, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  H5Dclose(d);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(f);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

// A step's field leaves its chunks of zeros out (HDF5 reads them as the fill value, zero): values
// read back bit for bit, -0.0 included, through our reader and through libxdmf.
TEST(UGS_FIELDS_SUITE, ChunksOfZerosAreNotStored) {
  const auto dir = test::temp_dir("fields-sparse");
  const std::size_t n = 100000;  // 3 components: 300,000 values, 5 chunks of 65,536 values
  const Mesh m = many_node_mesh(n);
  Field zero{"zero", 1, std::vector<double>(n, 0.0)};
  Field u{"u", 3, std::vector<double>(3 * n, 0.0)};
  for (std::size_t i = 30000; i < 30010; ++i) u.values[3 * i + 1] = 1.0 / (1.0 + static_cast<double>(i));  // chunk 1
  u.values[3 * 99999 + 2] = -0.0;                                                                         // the last chunk
  Field dense = test::sample_field("dense", 3, n, 0, 0.5);
  {
    FieldSeriesWriter w((dir / "s.h5").string(), m);
    w.add_step("2000-01-01", 0, std::vector<Field>{zero, u, dense});
    w.commit();
  }
  EXPECT_EQ(storage_size(dir / "s.h5", "/steps/000000/node/zero"), 0u);
  const hsize_t su = storage_size(dir / "s.h5", "/steps/000000/node/u");
  EXPECT_GT(su, 0u);
  EXPECT_LT(su, storage_size(dir / "s.h5", "/steps/000000/node/dense") / 2);
  FieldSeriesReader r((dir / "s.h5").string());
  for (const Field* f : {&zero, &u, &dense}) {
    const Field back = r.node_field(0, f->name);
    EXPECT_EQ(back.components, f->components);
    EXPECT_TRUE(same_bits(back.values, f->values)) << f->name;
  }
  EXPECT_TRUE(std::signbit(r.node_field(0, "u").values[3 * 99999 + 2]));
  auto g = read_xdmf(dir / "s.xdmf")->getGridCollection(0)->getUnstructuredGrid(0);
  expect_xdmf_attribute(g, u, XdmfAttributeCenter::Node());
  expect_xdmf_attribute(g, zero, XdmfAttributeCenter::Node());
  fs::remove_all(dir);
}

// The restart state beside the results: the mesh copied from the open results writer reads back
// as the mesh itself, and its index is the results' one.
TEST(UGS_FIELDS_SUITE, MeshCopiedFromAnOpenWriter) {
  const auto dir = test::temp_dir("fields-copy");
  const Mesh m = test::faulted_cube_mesh();
  FieldSeriesWriter results((dir / "r.h5").string(), m);
  {
    FieldSeriesWriter copy((dir / "c.h5").string(), results);
    EXPECT_EQ(copy.cell_count(), results.cell_count());
    const std::vector<Field> node = {test::sample_field("u", 3, m.num_nodes(), 0, -7.0)};
    const std::vector<Field> cell = {test::sample_field("chi", 1, copy.cell_count(), 0, 0.1)};
    copy.add_step(kDates[0], kTimes[0], node, cell);
    copy.commit();
    results.add_step(kDates[0], kTimes[0], node, cell);
  }
  EXPECT_THROW(FieldSeriesWriter("-", results), InputError);
  results.commit();
  EXPECT_THROW(FieldSeriesWriter((dir / "late.h5").string(), results), std::logic_error);
  FieldSeriesReader a((dir / "r.h5").string()), b((dir / "c.h5").string());
  EXPECT_EQ(b.node_tags(), m.node_tags);
  EXPECT_EQ(b.coordinates(), m.nodes);
  EXPECT_EQ(b.cell_types(), a.cell_types());
  EXPECT_EQ(b.cells(ElementType::Tetrahedron), connectivity(m, ElementType::Tetrahedron));
  EXPECT_EQ(b.cells(ElementType::Prism), connectivity(m, ElementType::Prism));
  EXPECT_EQ(b.cell_tags(), a.cell_tags());
  EXPECT_EQ(b.materials(), a.materials());
  expect_same(b.cell_field(0, "chi"), a.cell_field(0, "chi"));
  expect_same_index(dir, "r", "c");
  fs::remove_all(dir);
}

// A volume without interface prisms: its XDMF topology is its tetrahedra, no "Mixed" copy.
TEST(UGS_FIELDS_SUITE, OneTypeWithCellsIsNotMixed) {
  const auto dir = test::temp_dir("fields-onetype");
  const Mesh m = test::unit_cube_mesh();  // tetrahedra and boundary triangles, no prisms
  const Series s = write_series(dir / "t.h5", m);
  FieldSeriesReader r((dir / "t.h5").string());
  EXPECT_EQ(r.cell_types(), (std::vector<ElementType>{ElementType::Tetrahedron, ElementType::Prism}));
  EXPECT_EQ(r.cells(ElementType::Tetrahedron), connectivity(m, ElementType::Tetrahedron));
  EXPECT_EQ(test::slurp(dir / "t.xdmf").find("mixed_topology"), std::string::npos);
  auto g = read_xdmf(dir / "t.xdmf")->getGridCollection(0)->getUnstructuredGrid(2);
  EXPECT_EQ(g->getTopology()->getType(), XdmfTopologyType::Tetrahedron());
  EXPECT_EQ(g->getTopology()->getNumberElements(), 6u);
  expect_xdmf_attribute(g, s.cell[2][0], XdmfAttributeCenter::Cell());
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, NoStepsIsStillAMesh) {
  const auto dir = test::temp_dir("fields-empty");
  const Mesh m = test::faulted_cube_mesh();
  FieldSeriesWriter w((dir / "mesh.h5").string(), m);
  w.commit();
  FieldSeriesReader r((dir / "mesh.h5").string());
  EXPECT_TRUE(r.steps().empty());
  EXPECT_EQ(r.num_nodes(), m.num_nodes());
  auto domain = read_xdmf(dir / "mesh.xdmf");
  ASSERT_EQ(domain->getNumberUnstructuredGrids(), 1u);
  auto topo = domain->getUnstructuredGrid(0)->getTopology();
  topo->read();
  EXPECT_EQ(topo->getNumberElements(), 7u);
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, SameInputSameBytes) {
  const auto dir = test::temp_dir("fields-det");
  const Mesh m = test::faulted_cube_mesh();
  write_series(dir / "a.h5", m);
  ::sleep(1);  // a timestamp in the file would now differ
  write_series(dir / "b.h5", m);
  EXPECT_EQ(test::slurp(dir / "a.h5"), test::slurp(dir / "b.h5"));
  std::string xa = test::slurp(dir / "a.xdmf"), xb = test::slurp(dir / "b.xdmf");
  for (auto* x : {&xa, &xb}) x->erase(0, x->find("<Grid"));  // they differ only in the file name
  EXPECT_EQ(xa.size(), xb.size());
  fs::remove_all(dir);
}

// ugs-solve writes an output date's cell fields one at a time: the same file, byte for byte, as
// all of them given to add_step.
TEST(UGS_FIELDS_SUITE, CellFieldsAddedOneAtATimeGiveTheSameBytes) {
  const auto dir = test::temp_dir("fields-append");
  const Mesh m = test::faulted_cube_mesh();
  write_series(dir / "a.h5", m);
  {
    FieldSeriesWriter w((dir / "b.h5").string(), m);
    EXPECT_THROW(w.add_cell_field(test::sample_field("chi", 1, w.cell_count(), 0, 0.1)), std::logic_error);
    for (int k = 0; k < 3; ++k) {
      const std::vector<Field> node = {test::sample_field("dp", 1, m.num_nodes(), k, 0.25),
                                       test::sample_field("u", 3, m.num_nodes(), k, -7.0)};
      w.add_step(kDates[k], kTimes[k], node);
      w.add_cell_field(test::sample_field("stress", 6, w.cell_count(), k, 11.0));
      EXPECT_THROW(w.add_cell_field(test::sample_field("stress", 6, w.cell_count(), k, 11.0)), std::invalid_argument);
      EXPECT_THROW(w.add_cell_field(test::sample_field("short", 1, w.cell_count() - 1, k, 0.1)), std::invalid_argument);
      w.add_cell_field(test::sample_field("chi", 1, w.cell_count(), k, 0.1));
    }
    w.commit();
    EXPECT_THROW(w.add_cell_field(test::sample_field("late", 1, w.cell_count(), 0, 0.1)), std::logic_error);
  }
  EXPECT_EQ(test::slurp(dir / "a.h5"), test::slurp(dir / "b.h5"));
  expect_same_index(dir, "a", "b");
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, WithoutCommitNothingIsLeft) {
  const auto dir = test::temp_dir("fields-abort");
  const Mesh m = test::faulted_cube_mesh();
  {
    FieldSeriesWriter w((dir / "r.h5").string(), m);
    const std::vector<Field> f = {test::sample_field("dp", 1, m.num_nodes(), 0, 0.0)};
    w.add_step("2000-01-01", 0.0, f);
    EXPECT_FALSE(fs::is_empty(dir));  // the temporary
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, WriterRejectsMisuse) {
  const auto dir = test::temp_dir("fields-misuse");
  const Mesh m = test::faulted_cube_mesh();
  EXPECT_THROW(FieldSeriesWriter("-", m), InputError);
  EXPECT_THROW(FieldSeriesWriter((dir / "no" / "such" / "dir.h5").string(), m), InputError);
  FieldSeriesWriter w((dir / "r.h5").string(), m);
  const std::vector<Field> good = {test::sample_field("dp", 1, m.num_nodes(), 0, 0.0)};
  const std::vector<Field> short_field = {test::sample_field("dp", 1, m.num_nodes() - 1, 0, 0.0)};
  EXPECT_THROW(w.add_step("2000-01-01", 0, short_field), std::invalid_argument);
  const std::vector<Field> wide = {test::sample_field("wide", kMaxFieldComponents + 1, m.num_nodes(), 0, 0.0)};
  EXPECT_THROW(w.add_step("2000-01-01", 0, wide), std::invalid_argument);
  EXPECT_THROW(w.add_step("2000-13-01", 0, good), std::invalid_argument);
  w.add_step("2000-01-01", 0, good);
  EXPECT_THROW(w.add_step("2000-01-01", 1, good), std::invalid_argument);
  fs::remove_all(dir);
}

TEST(UGS_FIELDS_SUITE, ReaderErrorsNameFileFieldAndStep) {
  const auto dir = test::temp_dir("fields-errors");
  const Mesh m = test::faulted_cube_mesh();
  write_series(dir / "r.h5", m);
  const std::string h5 = (dir / "r.h5").string();
  FieldSeriesReader r(h5);
  EXPECT_EQ(test::input_error_of([&] { r.node_field(0, "p"); }),
            h5 + ": no node field 'p' at step 1964-01-01 (node fields: dp, u)");
  EXPECT_EQ(test::input_error_of([&] { r.cell_field(2, "dp"); }),
            h5 + ": no cell field 'dp' at step 2015-12-31T12:00:00 (cell fields: chi, stress)");
  EXPECT_EQ(test::input_error_of([&] { r.step("1970-01-01"); }), h5 + ": no step 1970-01-01 (3 steps, 1964-01-01 to 2015-12-31T12:00:00)");

  const std::string missing = (dir / "missing.h5").string();
  EXPECT_EQ(test::input_error_of([&] { FieldSeriesReader x(missing); }), missing + ": cannot open: No such file or directory");
  test::spit(dir / "text.h5", "date,p_MPa\n");
  EXPECT_EQ(test::input_error_of([&] { FieldSeriesReader x((dir / "text.h5").string()); }),
            (dir / "text.h5").string() + ": not an HDF5 file");

  // A truncated file is refused with one line, whatever part is missing.
  const std::string full = test::slurp(dir / "r.h5");
  for (std::size_t keep : {full.size() / 2, full.size() - 100, std::size_t(600)}) {
    test::spit(dir / "cut.h5", full.substr(0, keep));
    const std::string e = test::input_error_of([&] {
      FieldSeriesReader x((dir / "cut.h5").string());
      for (std::size_t k = 0; k < x.steps().size(); ++k) x.node_field(k, "u");
    });
    EXPECT_EQ(e.rfind((dir / "cut.h5").string() + ": ", 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  fs::remove_all(dir);
}

// What a field may allocate is bounded by the mesh's counts (its chunks of zeros need not be
// stored), so a field of more components than any writer writes is refused before its values are
// read, and a mesh claiming more nodes than its storage could hold when the file is opened.
TEST(UGS_FIELDS_SUITE, ReaderRefusesWhatTheMeshDoesNotBound) {
  const auto dir = test::temp_dir("fields-bounds");
  const Mesh m = test::faulted_cube_mesh();
  const std::string wide = (dir / "wide.h5").string(), huge = (dir / "huge.h5").string();
  write_series(wide, m);
  write_series(huge, m);
  add_unwritten_dataset(wide, "/steps/000000/node/wide", {m.num_nodes(), static_cast<hsize_t>(kMaxFieldComponents) + 1},
                        H5T_IEEE_F64LE);
  FieldSeriesReader r(wide);
  EXPECT_EQ(test::input_error_of([&] { r.node_field(0, "wide"); }),
            wide + ": /steps/000000/node/wide: 11 values of 65 components (expected 11 of at most 64 components)");
  const hsize_t nodes = hsize_t{1} << 30;
  add_unwritten_dataset(huge, "/mesh/coordinates", {nodes, 3}, H5T_IEEE_F64LE);
  add_unwritten_dataset(huge, "/mesh/node_tags", {nodes}, H5T_STD_U64LE);
  EXPECT_EQ(test::input_error_of([&] { FieldSeriesReader x(huge); }),
            huge + ": /mesh/coordinates claims 3221225472 values but stores only 0 bytes (damaged file?)");
  fs::remove_all(dir);
}

// Every node index of the cells and every coordinate is checked by the reader itself, so no caller
// indexes with a damaged value: a node index past the nodes and a NaN coordinate are one line each,
// naming the file and the dataset.
TEST(UGS_FIELDS_SUITE, ReaderRefusesABadNodeIndexAndANonFiniteCoordinate) {
  const auto dir = test::temp_dir("fields-values");
  const Mesh m = test::faulted_cube_mesh();
  const std::string index = (dir / "index.h5").string(), coord = (dir / "coord.h5").string();
  write_series(index, m);
  write_series(coord, m);
  poke_dataset(index, "/mesh/tetrahedra", H5T_NATIVE_UINT32, 5, std::uint32_t{4294967295u});
  poke_dataset(coord, "/mesh/coordinates", H5T_NATIVE_DOUBLE, 4, std::numeric_limits<double>::quiet_NaN());
  FieldSeriesReader ri(index), rc(coord);
  EXPECT_EQ(test::input_error_of([&] { ri.cells(ElementType::Tetrahedron); }),
            fmt::format("{}: /mesh/tetrahedra: cell 1 has node index 4294967295 (expected below the {} nodes of "
                        "/mesh/coordinates)", index, m.num_nodes()));
  EXPECT_EQ(ri.coordinates(), m.nodes);  // the other datasets still read
  EXPECT_EQ(test::input_error_of([&] { rc.coordinates(); }),
            coord + ": /mesh/coordinates: node 1 has y = nan (expected finite coordinates)");
  EXPECT_EQ(rc.cells(ElementType::Tetrahedron), connectivity(m, ElementType::Tetrahedron));
  fs::remove_all(dir);
}

// A file written by the other HDF5 flavour's build reads back the same (UGS_OTHER_WRITER is the
// sample writer linked against the other flavour).
TEST(UGS_FIELDS_SUITE, ReadsTheOtherFlavoursFile) {
  const auto dir = test::temp_dir("fields-other");
  const auto h5 = dir / "other.h5";
  const auto res = test::run(std::string(UGS_OTHER_WRITER) + " " + h5.string());
  ASSERT_EQ(res.exit_code, 0) << res.err;
  const Mesh m = test::faulted_cube_mesh();
  FieldSeriesReader r(h5.string());
  ASSERT_EQ(r.steps().size(), 1u);
  expect_same(r.node_field(0, "u"), test::sample_field("u", 3, m.num_nodes(), 0, -7.0));
  EXPECT_EQ(r.coordinates(), m.nodes);
  fs::remove_all(dir);
}
