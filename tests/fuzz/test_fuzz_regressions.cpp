// Inputs that fuzzing found to crash a reader (corpus/<target>/regress-*), read by the normal build's
// readers: each must be refused with an InputError naming what is wrong. The fuzz test (label fuzz)
// runs them again under ASan/UBSan as seeds of its targets.
#include <gtest/gtest.h>

#include <string>

#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"

namespace {

const std::string kCorpus = std::string(UGS_SOURCE_DIR) + "/tests/fuzz/corpus/";

// Opens a field series and reads everything in it, as the fuzz target does; returns the message
// of the InputError, or "" if it read without one.
std::string read_all_fields(const std::string& path) {
  try {
    ugs::FieldSeriesReader r(path);
    (void)r.node_tags();
    (void)r.coordinates();
    for (ugs::ElementType t : r.cell_types()) (void)r.cells(t);
    (void)r.cell_tags();
    (void)r.materials();
    for (std::size_t s = 0; s < r.steps().size(); ++s) {
      for (const auto& n : r.node_field_names(s)) (void)r.node_field(s, n);
      for (const auto& n : r.cell_field_names(s)) (void)r.cell_field(s, n);
    }
  } catch (const ugs::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FuzzRegressions, SeedFieldSeriesReadsWhole) {
  const std::string path = kCorpus + "hdf5_fields/tet_two_steps.h5";
  EXPECT_EQ(read_all_fields(path), "");
  ugs::FieldSeriesReader r(path);
  EXPECT_EQ(r.num_nodes(), 4u);
  EXPECT_EQ(r.num_cells(), 2u);
  ASSERT_EQ(r.steps().size(), 2u);
  EXPECT_EQ(r.steps()[1].date, "1950-02-01");
  EXPECT_EQ(r.cell_field(1, "stress").components, 6);
}

// A dataset whose type message says "1024-bit integer": HDF5's conversion overran its buffer
// (ASan: heap-buffer-overflow in H5VM_memcpyvv under H5Dread).
TEST(FuzzRegressions, HugeIntegerTypeIsRefused) {
  const std::string path = kCorpus + "hdf5_fields/regress-int1024-type.h5";
  EXPECT_EQ(read_all_fields(path),
            path + ": /mesh/prisms: not stored as plain numbers (expected integers or IEEE floats of 1 to 8 bytes)");
}

// /mesh/tetrahedra (6 x 4) with chunks of 6 x 524548 (a mutated layout message): HDF5 copied past its
// chunk buffer (ASan SEGV in H5VM_memcpyvv under H5D__select_read).
TEST(FuzzRegressions, ChunkLargerThanArrayIsRefused) {
  const std::string path = kCorpus + "hdf5_fields/regress-chunk-larger-than-array.h5";
  EXPECT_EQ(read_all_fields(path),
            path + ": /mesh/tetrahedra: its chunks (6 x 524548) do not fit its shape (6 x 4) (damaged file?)");
}

// A step's 'time' attribute with two values was read into one double (stack overflow).
TEST(FuzzRegressions, TimeAttributeWithTwoValuesIsRefused) {
  const std::string path = kCorpus + "hdf5_fields/regress-time-two-values.h5";
  EXPECT_EQ(read_all_fields(path), path + ": /steps/000001: attribute 'time' is not a single number");
}

// A step's 'date' attribute with two strings was read into a buffer for one (heap overflow).
TEST(FuzzRegressions, DateAttributeWithTwoTextsIsRefused) {
  const std::string path = kCorpus + "hdf5_fields/regress-date-two-texts.h5";
  EXPECT_EQ(read_all_fields(path), path + ": /steps/000001: attribute 'date' is not a single text");
}

}  // namespace
