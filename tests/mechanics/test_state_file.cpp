// Restart state files written one field at a time (StateFileWriter, what ugs-solve does so rank 0
// never holds the whole state): the same bytes as the state given to one add_step, the fields in
// the file's order only, and nothing left behind without commit().
#include <gtest/gtest.h>

#include <algorithm>

#include "run_tool.hpp"
#include "ugs/mechanics/state_file.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

// Distinct values per field, cell and component, so a field written in another's place cannot pass.
std::vector<double> values(std::size_t count, int components, double seed) {
  std::vector<double> v;
  for (std::size_t i = 0; i < count; ++i)
    for (int k = 0; k < components; ++k) v.push_back(seed + static_cast<double>(i) / 7.0 + k * 0.125 + 1e-9 / (1 + i));
  return v;
}

mech::SavedState sample_state(const Mesh& m) {
  const std::size_t nc = m.count(ElementType::Tetrahedron);
  mech::SavedState s;
  s.u = values(m.num_nodes(), 3, -0.25);
  s.dp = values(nc, 1, -1.0e6);
  s.eps = values(nc, 6, 3.0e-4);
  s.dsig = values(nc, 6, -2.0e5);
  s.hypo = values(nc, 4, 26.0);
  return s;
}

// The state file `h5` restarts on `m` with the date 2001-04-01 (3.2e7 s) and every value of `s`.
void expect_state_reads_back(const fs::path& h5, const Mesh& m, const mech::SavedState& s) {
  std::string date;
  double time = 0;
  const mech::SavedState back = mech::read_state(h5.string(), m, date, time);
  EXPECT_EQ(date, "2001-04-01");
  EXPECT_EQ(time, 3.2e7);
  EXPECT_EQ(back.u, s.u);
  EXPECT_EQ(back.dp, s.dp);
  EXPECT_EQ(back.eps, s.eps);
  EXPECT_EQ(back.dsig, s.dsig);
  EXPECT_EQ(back.hypo, s.hypo);
}

}  // namespace

TEST(StateFile, WrittenOneFieldAtATimeGivesTheBytesOfOneStep) {
  const auto dir = test::temp_dir("state-file");
  const Mesh m = test::unit_cube_mesh();
  const mech::SavedState s = sample_state(m);
  {
    // The layout ugs-solve wrote before: every field given to one add_step.
    FieldSeriesWriter w((dir / "one.h5").string(), m);
    const Field nodes[] = {{"u", 3, s.u}};
    const Field cells[] = {{"dp", 1, s.dp}, {"eps", 6, s.eps}, {"dsig", 6, s.dsig}, {"hypo", 4, s.hypo}};
    w.add_step("2001-04-01", 3.2e7, nodes, cells);
    w.commit();
  }
  mech::write_state((dir / "streamed.h5").string(), m, "2001-04-01", 3.2e7, s);
  EXPECT_EQ(test::slurp(dir / "one.h5"), test::slurp(dir / "streamed.h5"));
  expect_state_reads_back(dir / "streamed.h5", m, s);
  fs::remove_all(dir);
}

// ugs-solve's state beside its results: the mesh copied from the open results writer, the state
// read back as written (zero cells included: their chunks are not stored) and restartable on the
// mesh itself.
TEST(StateFile, MeshCopiedFromTheResultsReadsBackTheSame) {
  const auto dir = test::temp_dir("state-copy");
  const Mesh m = test::unit_cube_mesh();
  mech::SavedState s = sample_state(m);
  std::fill(s.eps.begin(), s.eps.end(), 0.0);  // a linear model's
  FieldSeriesWriter results((dir / "r.h5").string(), m);
  {
    mech::StateFileWriter w((dir / "s.h5").string(), results, "2001-04-01", 3.2e7, s.u);
    w.add(mech::StateField::Dp, s.dp);
    w.add(mech::StateField::Eps, s.eps);
    w.add(mech::StateField::Dsig, s.dsig);
    w.add(mech::StateField::Hypo, s.hypo);
    w.commit();
  }
  results.commit();
  expect_state_reads_back(dir / "s.h5", m, s);
  fs::remove_all(dir);
}

TEST(StateFile, FieldsOutOfOrderOrMissingAreRefusedAndLeaveNothing) {
  const auto dir = test::temp_dir("state-file-misuse");
  const Mesh m = test::unit_cube_mesh();
  const mech::SavedState s = sample_state(m);
  {
    mech::StateFileWriter w((dir / "a.h5").string(), m, "2001-04-01", 0.0, s.u);
    EXPECT_THROW(w.add(mech::StateField::Eps, s.eps), std::logic_error);  // dp comes first
    w.add(mech::StateField::Dp, s.dp);
    w.add(mech::StateField::Eps, s.eps);
    EXPECT_THROW(w.commit(), std::logic_error);  // dsig and hypo missing
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}
