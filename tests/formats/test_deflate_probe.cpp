// deflate_probe: HDF5 datasets are deflated only where that shrinks them well.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "ugs/formats/deflate_probe.hpp"

using ugs::deflate_pays;

namespace {

// Stress-like values (Pa): every bit of the mantissa carries information.
std::vector<double> stresses(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> d(-2.0e7, 3.0e6);
  std::vector<double> v(n);
  for (auto& x : v) x = d(rng);
  return v;
}

bool pays(const std::vector<double>& v) { return deflate_pays(v.data(), v.size() * sizeof(double), sizeof(double)); }

}  // namespace

TEST(DeflateProbe, FullPrecisionStressesAreWrittenAsTheyAre) {
  EXPECT_FALSE(pays(stresses(6 * 500000, 1)));
  EXPECT_FALSE(pays(stresses(10, 2)));  // a tiny dataset grows under deflate
}

TEST(DeflateProbe, FieldsZeroInMostCellsAreDeflated) {
  auto v = stresses(1000000, 3);
  std::fill(v.begin(), v.begin() + 600000, 0.0);  // elastic rock, ordered first by material
  EXPECT_TRUE(pays(v));
}

TEST(DeflateProbe, StatesAndIndicesAreDeflated) {
  std::vector<double> state(1000000);
  for (std::size_t i = 0; i < state.size(); ++i) state[i] = static_cast<double>((i / 97) % 3);
  EXPECT_TRUE(pays(state));
  std::vector<std::uint32_t> conn(4 * 300000);
  for (std::size_t i = 0; i < conn.size(); ++i) conn[i] = static_cast<std::uint32_t>(i / 4 + (i % 4) * 17);
  EXPECT_TRUE(deflate_pays(conn.data(), conn.size() * 4, 4));
}

TEST(DeflateProbe, SamplesReachTheEndOfTheData) {
  // Compressible at the start only: the probe must not judge by the first sample alone.
  auto v = stresses(2000000, 4);
  std::fill(v.begin(), v.begin() + 100000, 0.0);
  EXPECT_FALSE(pays(v));
  EXPECT_FALSE(deflate_pays(nullptr, 0, 8));
}
