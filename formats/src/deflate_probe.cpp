#include "ugs/formats/deflate_probe.hpp"

#include <zlib.h>

#include <algorithm>
#include <vector>

namespace ugs {

bool deflate_pays(const void* data, std::size_t bytes, std::size_t element_size, const DeflateProbe& probe) {
  if (bytes == 0 || element_size == 0) return false;
  const auto* in = static_cast<const unsigned char*>(data);
  const std::size_t n_elem = bytes / element_size;
  const std::size_t per_sample = std::max<std::size_t>(1, std::min(n_elem, probe.sample_bytes / element_size));
  // Evenly spaced samples from the start to the end, without overlap.
  const std::size_t fit = n_elem / per_sample;
  const std::size_t k = std::max<std::size_t>(1, std::min<std::size_t>(std::max(probe.samples, 1), fit));
  std::vector<std::size_t> starts;
  for (std::size_t j = 0; j < k; ++j) starts.push_back(k == 1 ? 0 : j * (n_elem - per_sample) / (k - 1));
  std::vector<unsigned char> shuffled(per_sample * element_size);
  std::vector<unsigned char> packed(compressBound(static_cast<uLong>(shuffled.size())));
  std::size_t raw = 0, deflated = 0;
  for (const std::size_t s : starts) {
    const std::size_t n = std::min(per_sample, n_elem - s);
    // HDF5's shuffle: byte b of every element, then byte b + 1, ...
    for (std::size_t b = 0; b < element_size; ++b)
      for (std::size_t i = 0; i < n; ++i) shuffled[b * n + i] = in[(s + i) * element_size + b];
    uLongf out = static_cast<uLongf>(packed.size());
    if (compress2(packed.data(), &out, shuffled.data(), static_cast<uLong>(n * element_size), probe.level) != Z_OK)
      return true;  // cannot judge: keep the filters
    raw += n * element_size;
    deflated += out;
  }
  return static_cast<double>(deflated) <= probe.worth * static_cast<double>(raw);
}

}  // namespace ugs
