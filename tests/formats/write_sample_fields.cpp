// Writes a one-step field series of the faulted test cube to argv[1]. Built against each HDF5
// flavour so that each flavour's test can read a file the other one wrote.
#include <cstdio>
#include <exception>

#include "sample_fields.hpp"
#include "ugs/formats/fields.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s out.h5\n", argv[0]);
    return 2;
  }
  try {
    const ugs::Mesh m = ugs::test::faulted_cube_mesh();
    ugs::FieldSeriesWriter w(argv[1], m);
    const std::vector<ugs::Field> node = {ugs::test::sample_field("u", 3, m.num_nodes(), 0, -7.0)};
    w.add_step("2000-01-01", 0.0, node);
    w.commit();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", argv[0], e.what());
    return 1;
  }
  return 0;
}
