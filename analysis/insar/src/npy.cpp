#include "ugs/insar/npy.hpp"

#include <bit>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/formats/io.hpp"

namespace ugs::insar {

namespace {

void write(const std::string& path, const void* data, std::size_t bytes, std::size_t count, const char* descr,
           const std::vector<std::size_t>& shape) {
  static_assert(std::endian::native == std::endian::little, "NPY writer assumes a little-endian host");
  std::size_t n = 1;
  std::string dims;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    n *= shape[i];
    dims += fmt::format("{}{}", shape[i], shape.size() == 1 ? "," : (i + 1 < shape.size() ? ", " : ""));
  }
  if (n != count) throw std::invalid_argument(fmt::format("write_npy {}: {} values for shape ({})", path, count, dims));
  std::string header = fmt::format("{{'descr': '{}', 'fortran_order': False, 'shape': ({}), }}", descr, dims);
  // Magic (6) + version (2) + length (2) + header + '\n', padded to a multiple of 64.
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  OutputFile f(path);
  const unsigned char magic[8] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
  f.write(magic, 8);
  const std::uint16_t len = static_cast<std::uint16_t>(header.size());
  f.write(&len, 2);
  f.write(header);
  if (bytes) f.write(data, bytes);
  f.commit();
}

}  // namespace

void write_npy(const std::string& path, std::span<const double> v, const std::vector<std::size_t>& shape) {
  write(path, v.data(), v.size_bytes(), v.size(), "<f8", shape);
}

void write_npy(const std::string& path, std::span<const std::int32_t> v, const std::vector<std::size_t>& shape) {
  write(path, v.data(), v.size_bytes(), v.size(), "<i4", shape);
}

}  // namespace ugs::insar
