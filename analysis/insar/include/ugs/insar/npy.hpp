// NumPy .npy files (format 1.0, little-endian, C order): how ugs-report hands arrays to its
// plotting script (no pickles: numpy.load(..., allow_pickle=False) reads them).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ugs::insar {

void write_npy(const std::string& path, std::span<const double> values, const std::vector<std::size_t>& shape);
void write_npy(const std::string& path, std::span<const std::int32_t> values, const std::vector<std::size_t>& shape);

}  // namespace ugs::insar
