// The faults as the contact solver sees them (thesis 3.5.2), built once on rank 0 from the faulted
// mesh (interface elements of ugs-faultinsert, docs/faults.md) and the case file's [[fault]] entries.
//
// Node pairs. Every interface element (6-node prism: nodes 1-3 on side 1, nodes 4-6 their twins)
// contributes its area A_e / 3 to each of its three node pairs (eq. 3.53); a pair carries one
// Lagrange multiplier vector, piecewise constant on its share A_q of the fault (eq. 3.52), and the
// coupling matrix C is lumped node to node: C_q = A_q R_q on side 2, -A_q R_q on side 1. Tip nodes
// (one id on both sides) carry no multiplier: the displacement is continuous there.
//
// Local frame (eq. 3.43) per pair: the normal n is the area-weighted mean of the unit normals of the
// pair's interface elements, oriented from side 1 to side 2 (the thesis' Gamma_T to Gamma_B); the
// first tangent is the strike (horizontal, n x e_z normalised; e_x on a horizontal fault) and the
// second the dip direction t2 = n x t1, so (t1, t2, n) is right-handed. On a planar fault every
// pair and every element share the frame. Multipliers are the total traction on side 1 (the force
// side 2 exerts per unit area, tension positive) in that frame: lambda = (tau_strike, tau_dip, sigma_n).
// A pair whose twins share prescribed components (a fault reaching a roller or fixed side) has the
// reduced frame of constraint_frame instead: multipliers on the free part of the jump only.
//
// Junctions: pairs of several faults meeting at a node form cycles of twin constraints (an X-junction
// has four copies and four pairs), of which one per cycle is implied by the others. The pair that
// closes a cycle (in fault, then element order) is marked redundant and its constraint rows get a
// tiny perturbed-Lagrangian term, so the saddle-point matrix stays non-singular.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ugs/contact/dof_mask.hpp"
#include "ugs/fem/voigt.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/model.hpp"

namespace ugs::contact {

struct FaultProperties {
  std::string name;       // without "fault:"
  std::string where;      // case file line of its [[fault]] entry
  double cohesion = 0;    // Pa
  double friction_deg = 30;
  double mu = 0;          // tan(friction angle)
  std::size_t elements = 0, pairs = 0, tip_nodes = 0;
  double area = 0;        // m2
};

struct NodePair {
  std::uint32_t side1 = 0, side2 = 0;  // mesh node indices (twins)
  std::uint64_t tag1 = 0, tag2 = 0;    // their node tags
  std::int32_t fault = 0;              // index into FaultModel::faults
  double area = 0;                     // A_q [m2]: a third of each of its triangles (the coupling's weight)
  // The area the outputs count (slip and open areas, the per-pair CSV): each triangle's area split
  // over its corners that are pairs, so that tip nodes' thirds are not lost at the fault's edges [m2].
  double reported_area = 0;
  Point3 x{};                          // position
  std::array<double, 9> R{};           // row-major 3x3, columns t1 (strike), t2 (dip), n
  std::array<double, 3> lambda0{};     // initial total traction, local frame [Pa]
  double p0 = 0;                       // initial fluid pressure on the fault [Pa]
  double k = 0;                        // stiffness scale E_oed / h of the adjacent elements [Pa/m]
  std::uint8_t fixed1 = 0, fixed2 = 0; // prescribed displacement components of the twins (bits x, y, z)
  std::uint8_t active = 7;             // bit j: local component j carries a multiplier (constraint_frame)
  bool redundant = false;              // closes a cycle of pairs at a junction
  std::int32_t junction = -1;          // the junction whose cycle the pair belongs to (-1: none)

  // The pair obeys the friction law with its normal and at least one shear direction free: it counts
  // in the fault statistics (max chi, slipping and open pairs) and the scenario search.
  bool frictional() const { return normal_active(active) && (is_active(active, kStrike) || is_active(active, kDip)); }
};

// The output surface: one triangle per interface element (its side-1 face), one node per node pair
// of each fault (and one per tip node), in groups fault:<name> of dimension 2.
struct FaultSurface {
  Mesh mesh;
  std::vector<std::int64_t> node_pair;                // pair of each surface node, -1 at tip nodes
  std::vector<std::vector<std::uint32_t>> tip_neighbours;  // for tip nodes: surface nodes sharing a triangle
  std::vector<std::int32_t> triangle_fault;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // surface node indices (output order)
};

struct FaultModel {
  std::vector<FaultProperties> faults;
  std::vector<NodePair> pairs;
  FaultSurface surface;
  std::size_t redundant_pairs = 0;
  std::size_t junctions = 0;           // groups of pairs joined in a cycle (NodePair::junction)
  std::size_t inactive_pairs = 0;      // pairs on prescribed boundaries that are not frictional()
  std::size_t boundary_pairs = 0;      // pairs with a reduced frame (some jump component prescribed)
};

// Initial state of the faults: total stress (thesis Voigt order, Pa, tension positive) and fluid
// pressure at a point; `biot` and `k` (the effective stress ratios k_Hmax, k_hmin) are those of the
// rock on side 1 (the hanging wall), area-weighted over the pair's elements where it changes;
// `gas` is the gas column of the side-1 material with the largest share of the pair's area (the
// pore fluid of a pair in a pool's gas cap is gas).
struct InitialFaultState {
  std::function<fem::Vec6(const Point3& x, double biot, const std::array<double, 2>& k, const GasColumn& gas)> total_stress;
  std::function<double(const Point3& x, const GasColumn& gas)> pressure;
};

// The geostatic state of the case (mech::InitialState): sigma = sigma' - biot p0 I, p = p0.
InitialFaultState geostatic_fault_state(const mech::InitialState& init);

// Builds the pairs, frames, initial tractions and the output surface. InputError (exit 2) for:
// [[fault]] entries whose fault:<name> has no interface elements in the mesh, interface elements in
// a fault the case does not describe or in no fault group, interface elements whose nodes 4-6 are not
// twins of nodes 1-3 (different coordinates), degenerate ones, and ones whose sides are not faces of
// tetrahedra of the mesh.
FaultModel build_fault_model(const Mesh& mesh, const CaseFile& cs, const mech::Model& model, const InitialFaultState& init);

// Local frame (t1, t2, n) of a unit normal, row-major with the axes as columns.
std::array<double, 9> fault_frame(const Point3& n);

// The constraint frame of a node pair whose twins have the prescribed components fixed1, fixed2
// (bits x, y, z). The relative displacement g = u2 - u1 lives in S = span{e_c : c free on either
// twin} (a component prescribed on both twins has no jump: rollers and fixed sides prescribe zero).
// The frame R (columns: two tangents and the normal slot, mutually orthogonal) puts a basis of S in
// the active slots and the directions normal to S in held slots (no multiplier: their traction is
// the support's reaction), so the active constraint rows are exactly independent whatever the tilt
// of n (no threshold on the geometry decides which rows exist):
//   - S = R^3: the fault frame, active 7;
//   - the normal's part in S, m = P_S n, with |m| > kNormalInFree: the normal slot is m (not
//     normalised: m . g = n . g, the fault's normal gap; the multiplier is the fault's normal
//     traction), the tangent slots the unit direction of S normal to m (active; a shear direction
//     of the fault) and the prescribed axes (held);
//   - |m| <= kNormalInFree (the free directions lie in the fault plane): the normal slot is the part
//     of n normal to S (held: the traction keeps its initial value), S in the tangent slots (active,
//     friction under that normal traction);
//   - S empty (fully fixed twins): the fault frame, nothing active.
// The tangent slots follow the fault frame's (strike, dip) as closely as the subspaces allow.
struct ConstraintFrame {
  std::array<double, 9> R{};
  std::uint8_t active = 7;
};
inline constexpr double kNormalInFree = 1e-3;  // 0.06 degrees; meshgen's normals tilt ~2e-6 rad
ConstraintFrame constraint_frame(const Point3& n, std::uint8_t fixed1, std::uint8_t fixed2);

}  // namespace ugs::contact
