// Test support: damage one value of a dataset in an HDF5 file written by FieldSeriesWriter (a node
// index, a coordinate), as a corrupted or hand-made file would hold it.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace ugs::test {

template <class T>
inline void h5_poke(const std::string& file, const std::string& dataset, std::size_t index, T value) {
  const hid_t mem = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_UINT32;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("h5_poke: cannot open " + file);
  const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  if (d < 0) throw std::runtime_error("h5_poke: no dataset " + dataset);
  const hid_t space = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<T> v(static_cast<std::size_t>(n));
  H5Dread(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  v.at(index) = value;
  H5Dwrite(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

}  // namespace ugs::test
