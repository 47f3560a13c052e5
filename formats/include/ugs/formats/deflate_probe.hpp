#pragma once
// Whether HDF5's shuffle + deflate filters are worth their time on a dataset (hdf5_fields.cpp).
#include <cstddef>

namespace ugs {

// Deflating pays when the shuffled bytes shrink to at most `worth` of their size. Judged on up to
// `samples` evenly spaced samples of `sample_bytes` (the first at the start, the last at the end),
// so the probe costs a few milliseconds whatever the dataset's size. Stress and strain fields in
// double precision shrink only to ~0.8 and cost zlib's whole time; indices, states and fields
// that are zero in most cells shrink to ~0.1.
struct DeflateProbe {
  int level = 1;
  double worth = 0.7;
  int samples = 16;
  std::size_t sample_bytes = std::size_t{1} << 15;
};

bool deflate_pays(const void* data, std::size_t bytes, std::size_t element_size, const DeflateProbe& probe = {});

}  // namespace ugs
