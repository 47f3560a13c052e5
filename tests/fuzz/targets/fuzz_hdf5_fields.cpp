// HDF5 field series reader (formats/src/hdf5_fields.cpp), as ugs-solve (--pressure, --restart),
// ugs-sample, ugs-calibrate and ugs-report call it: the input is written to a file (HDF5 opens
// files by name) and every accessor is called on what opens.
#include <algorithm>

#include "fuzz_support.hpp"
#include "ugs/formats/fields.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("fields.h5", data, size);
  ugs::fuzz::outcome([&] {
    ugs::FieldSeriesReader r(path);
    (void)r.num_nodes();
    (void)r.num_cells();
    (void)r.node_tags();
    (void)r.coordinates();
    for (ugs::ElementType t : r.cell_types()) (void)r.cells(t);
    (void)r.cell_tags();
    (void)r.materials();
    const std::size_t steps = std::min<std::size_t>(r.steps().size(), 8);
    for (std::size_t s = 0; s < steps; ++s) {
      ugs::fuzz::outcome([&] { (void)r.step(r.steps()[s].date); });
      ugs::fuzz::outcome([&] {
        for (const auto& name : r.node_field_names(s)) ugs::fuzz::outcome([&] { (void)r.node_field(s, name); });
      });
      ugs::fuzz::outcome([&] {
        for (const auto& name : r.cell_field_names(s)) ugs::fuzz::outcome([&] { (void)r.cell_field(s, name); });
      });
    }
  });
  return 0;
}
