// The bit masks of a node pair (fault_model.hpp NodePair) by name:
//   fixed1, fixed2  bit k: displacement component k (0 x, 1 y, 2 z) of the twin is prescribed
//   active          bit j: local traction component j (0 strike, 1 dip, 2 normal) acts on some free
//                   degree of freedom (else it keeps its initial traction: the support carries it)
#pragma once
#include <cstdint>

namespace ugs::contact {

inline constexpr int kStrike = 0, kDip = 1, kNormal = 2;

// Displacement component `axis` (0 x, 1 y, 2 z) of a node with prescribed-components mask `fixed`.
constexpr bool is_fixed(std::uint8_t fixed, int axis) { return ((fixed >> axis) & 1) != 0; }
constexpr bool is_free(std::uint8_t fixed, int axis) { return !is_fixed(fixed, axis); }

// Local traction component (kStrike, kDip, kNormal) of a pair with mask `active`.
constexpr bool is_active(std::uint8_t active, int component) { return ((active >> component) & 1) != 0; }
// The pair's normal acts on free degrees of freedom (else it keeps its initial traction and the shear
// obeys friction under it; fault_model.hpp constraint_frame).
constexpr bool normal_active(std::uint8_t active) { return is_active(active, kNormal); }

}  // namespace ugs::contact
