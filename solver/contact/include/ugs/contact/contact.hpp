// Fault contact with Lagrange multipliers (thesis 3.3, 3.5.2; Franceschini et al. 2016), coupled to
// the continuous solver through mech::Coupling: MechanicsSolver keeps its elements, tangent and
// sub-steps; this class adds the multiplier block and solves the saddle-point Newton system
//
//   [ K   C ] [du]     [ f_ext - f_int(u) - C (lambda - lambda_0) ]
//   [ B   D ] [dl] = - [ F(u, lambda)                              ]       (eqs. 3.60-3.68)
//
// with C the node-to-node coupling (fault_model.hpp), and B, D the derivatives of the contact
// equations of each node pair (pair_law.hpp) in their current state: constraint rows for stick
// (B = k C^T, D = 0) and for the normal of a slipping pair, the friction law for the shear of a
// slipping pair (the blocks 3.63-3.64, with the friction written in the multiplier rows) and
// prescribed tractions for open pairs. Newton updates the states at every iteration (active set)
// and stops when the unbalanced forces are below the tolerance and no state changed.
//
// Linear solvers (PETSc):
//   mumps       the assembled saddle-point matrix factorised by MUMPS (LU): robust, for small and
//               medium models
//   fieldsplit  FGMRES with a Schur-complement field split: the displacement block augmented with
//               the constraint rows (augmented Lagrangian, K + gamma C W B) under algebraic multigrid
//               (GAMG; BoomerAMG through PETSc options), the multiplier block by the selfp approximation
//               D - B diag(K_gamma)^-1 C; scalable. PETSc options with the prefix -contact_ tune it
//               (-contact_ksp_monitor, -contact_fieldsplit_u_pc_type hypre, ...).
//   auto        mumps up to ContactOptions::direct_limit unknowns, fieldsplit above.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/pair_law.hpp"
#include "ugs/mechanics/coupling.hpp"

namespace ugs::contact {

// Named "auto", "mumps" and "fieldsplit" (ugs/driver/names.hpp).
enum class SaddleSolver { Auto, Mumps, FieldSplit };

struct ContactOptions {
  SaddleSolver solver = SaddleSolver::Auto;
  std::size_t direct_limit = 50000;   // unknowns up to which auto takes MUMPS
  double augmentation = 1.0;          // gamma of the augmented Lagrangian (field split)
  // Perturbed-Lagrangian weight of the pair closing a cycle at a junction (fault_model.hpp). While
  // every pair of the cycle sticks, that pair's constraint follows from the others' and the term
  // only fixes the multipliers' circulation around the cycle, which no other equation sees: the
  // weight then changes no answer, only how well the circulation is determined. At 1e-6 its
  // residual was below any Newton tolerance and junction tractions drifted with the solver's
  // iterates from step to step (coarsened thesis history, field split: max chi on the line where
  // the regional faults cross 0.1056 at tolerance 1e-8 against 0.1174 at 1e-11 by 1964). Where a
  // pair of the cycle slips or opens the closing pair's constraint is its own, and the small weight
  // holds it to 1e-6 of the multiplier change over k (at 1 the slab's slipping junction moved 1.3 %).
  double closed_regularization = 1.0;
  double regularization = 1e-6;
  int max_state_changes = 4;          // changes of one pair within a (sub-)step before it is cycling
  bool reuse_preconditioner = true;   // field split: keep the hierarchy while it converges well
};

// The committed state per node pair, gathered on rank 0 in FaultModel order.
struct PairResults {
  std::vector<double> lambda;      // 3 per pair: total traction in the local frame [Pa]
  std::vector<double> g;           // 3 per pair: relative displacement in the local frame [m]
  std::vector<double> p_f;         // fluid pressure on the fault [Pa]
  std::vector<std::uint8_t> state; // PairState
};

struct ContactStats {
  std::size_t solves = 0, linear_iterations = 0, state_changes = 0, preconditioner_setups = 0;
  double seconds = 0;
};

class FaultContact final : public mech::Coupling {
public:
  // Collective. `model` is used on rank 0 only (may be null elsewhere) and must outlive setup().
  FaultContact(MPI_Comm comm, const FaultModel* model, const ContactOptions& options);
  ~FaultContact() override;
  FaultContact(const FaultContact&) = delete;
  FaultContact& operator=(const FaultContact&) = delete;

  // Collective: the fluid pressure change on the fault [Pa] (rank 0: one value per pair, FaultModel
  // order) reached at the end of the next MechanicsSolver::advance; sub-steps interpolate linearly.
  void set_pressure_change(const std::vector<double>& dp_pairs);
  // Collective.
  PairResults gather() const;
  // The committed state of this rank's pairs (for scenario reruns from a saved point).
  struct Snapshot {
    std::vector<double> lambda, g, dp;
    std::vector<std::uint8_t> state;
  };
  Snapshot save() const;
  void restore(const Snapshot& s);
  // Collective: the committed state of every pair on rank 0 in FaultModel order (restart files),
  // and back from rank 0's copy (its sizes checked on rank 0).
  Snapshot gather_snapshot() const;
  void restore_gathered(const Snapshot& all);

  const ContactStats& stats() const;
  std::string description() const;  // the saddle-point solver in use
  std::size_t global_pairs() const;

  // mech::Coupling
  void setup(const mech::CouplingContext& ctx) override;
  void begin_step() override;
  void begin_substep(double fraction) override;
  double residual(Vec u, Vec r) override;
  bool settled() override;
  std::string stalled() override;
  mech::CouplingSolve solve(Mat A, Vec r, Vec du, double rtol) override;
  std::string diagnosis() override;
  void commit() override;
  void revert_substep() override;
  void revert_step() override;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs::contact
