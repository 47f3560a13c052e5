// The key of a triangular face in hash maps: its three node indices sorted, so that a face is found
// from any element that has it, whatever the element's local node order (tetrahedron faces against
// boundary or fault triangles).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace ugs {

using FaceKey = std::array<std::uint32_t, 3>;

inline FaceKey face_key(FaceKey f) {
  std::sort(f.begin(), f.end());
  return f;
}

inline FaceKey face_key(std::uint32_t a, std::uint32_t b, std::uint32_t c) { return face_key(FaceKey{a, b, c}); }

struct FaceKeyHash {
  std::size_t operator()(const FaceKey& f) const {
    std::uint64_t h = f[0];
    h = h * 0x9E3779B97F4A7C15ull ^ f[1];
    h = h * 0x9E3779B97F4A7C15ull ^ f[2];
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace ugs
