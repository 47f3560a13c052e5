// Newton, the named part of the mechanics solver that iterates one (sub-)step to equilibrium
// (newton.cpp): the first tangents, the forcing term of each correction with its bound, the knee
// holds, and the convergence test. It is given, by reference, what it reads and what it changes,
// and calls the solver's operations (external force, residual, assembly, linear solve); the
// solver's Impl (solver_impl.hpp) owns it. Private to ugs_mechanics.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <petscksp.h>

#include "local_mesh.hpp"
#include "predictor.hpp"
#include "ugs/fem/tet4.hpp"
#include "ugs/mechanics/coupling.hpp"
#include "ugs/mechanics/solver.hpp"

namespace ugs::mech {

struct HypoStateStore;       // solver_impl.hpp
struct PreconditionerReuse;  // solver_impl.hpp

// The result of one linear solve (linear_solve.cpp), what Newton's correction solve returns.
struct LinearSolveResult {
  int iterations = 0;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  double reduction = 0;
  // Why the preconditioner was set up for this solve (-ugs_newton_monitor): "" kept, "first",
  // "branches" (elements changed stiffness), "rate" (iterations per decade), "budget" (a kept
  // one failed and the solve was repeated).
  const char* setup = "";
};

// Newton: the iteration of one (sub-)step with the knee holds (newton.cpp). It is given, by
// reference, what it reads and what it changes, and the solver's operations it calls.
class Newton {
 public:
  // What Newton reads.
  struct Reads {
    const SolverOptions& opt;               // max_newton, tolerance
    const LocalMesh& lm;                    // materials, ownership, communicator
    const std::vector<fem::Tet4>& geo;      // held_off_branch's force bound
    const std::vector<double>& s0;          // initial effective vertical stress [MPa]
    const std::vector<double>& dp_cell;     // pressure change of the committed state
    const bool& has_hyp;                    // some rank has hypo-plastic elements
    Coupling* const& coupling;              // extra unknowns (fault contact) or null
    const PreconditionerReuse& reuse;       // setups (counted in the report)
    const Mat& A;                           // the tangent (the predictor's projection)
    const Vec& r;                           // the residual (written by residual())
  };
  // What Newton changes: the hold fields of the state store (guess, piece, flips, hold,
  // hold_dir; the trial states change through residual()), the values of u (u_save keeps the
  // start of the (sub-)step) and of the correction du.
  struct Changes {
    HypoStateStore& hyp;
    const Vec& u;
    const Vec& u_save;
    const Vec& du;
  };
  // The solver's operations Newton calls.
  struct Operations {
    std::function<void(const std::vector<double>&)> external_force;  // f_ext of a pressure change
    std::function<double()> residual;     // r = f_ext - f_int(u); the trial states; returns ||r||
    std::function<void()> assemble;       // A from the trial states
    std::function<LinearSolveResult(double rtol, bool guess)> solve;  // A du = r
    std::function<double()> load_norm;    // ||f_ext|| over the free components (after external_force)
  };

  Newton(Reads reads, Changes changes, Operations ops) : in_(reads), out_(changes), op_(std::move(ops)) {}

  // Iterates u towards the equilibrium with the pressure change dp_target (per local cell).
  // Returns false (why says why) when it does not converge; rep gets the iteration counts.
  bool iterate(const std::vector<double>& dp_target, StepReport& rep, std::string& why);

  Predictor predictor;

 private:
  // An element that changes branch twice within a (sub-)step sits at the knee, where its stiffness
  // jumps by c_R (at J = 0 on the virgin curve even its lateral stress jumps): Newton would cycle.
  // It is held on the unloading/reloading branch (the stiffer one: Newton with the softer tangent
  // overshoots); the residual is then smooth (hypoplastic.hpp). From Newton iteration
  // kHoldOnFirstChangeFrom on, one change is enough: on large meshes a tail of elements near the
  // pressure front (J ~ 0) changes branch once each, a few per iteration, and keeps the residual
  // from converging (thesis-scale box, 1950-02: 21 iterations with 2 changes, or no convergence on
  // another partition). The held branches are checked at convergence (held_off_branch).
  static constexpr int kHoldOnFirstChangeFrom = 3;
  // Corrections::Bounded: no correction leaves more than kCorrectionBound x tolerance x r_0 of
  // residual, so the iterates on which the holds are decided are within 50 times the Newton
  // tolerance of an exact Newton's (docs/mechanics.md: the held set first changed at 10,000 x
  // tolerance on test_locked_history, at 200 x on the scale-0.05 thesis box: a margin of 4 there).
  static constexpr double kCorrectionBound = 50;
  // The first tangent of each hypo-plastic element (its direction, unless its pressure change
  // reverses) and no holds yet.
  void first_tangents(const std::vector<double>& dp_target);
  // Whether some element (on any rank) may change branch in this step: then the corrections start
  // inexact (eta = 1e-4), else a linear step is solved exactly at once.
  bool step_is_nonlinear() const;
  // The relative tolerance of the linear solve of a correction: the forcing term eta, bounded by
  // what reaches the Newton tolerance and, for Bounded corrections, by kCorrectionBound.
  double correction_rtol(Corrections corrections, double eta, double r0, double rk) const;
  // The convergence test: ||r|| <= tolerance x ||r_0|| and, with a coupling, its state settled.
  bool converged(double rk, double r0) const;
  // The next forcing term (Eisenstat-Walker choice 2 with gamma = 0.9, at most 0.1), at least 1e-2
  // while elements still change branch.
  double next_forcing(double eta, double rk, double rprev, long long moved_all) const;
  void track_branches(int k);
  // Whether an element's tangent changed with its loading phase since `phase_before`.
  bool tangent_moved(std::size_t h, int phase_before) const;

  // The consistency of the held branches at a converged iterate. A held element whose J ended on
  // the other side of its knee, at distance delta = J - J_knee, is a point of the law's graph
  // after a vertical strain change of delta (the stress moves by delta Dhat e_z / c_t): its
  // residual is within ||V B^T delta Dhat e_z / c_t|| of the residual of a state that obeys the
  // law everywhere (at the knee the response is set-valued: either branch's stiffness is
  // admissible). Returns the sum of these bounds over the inconsistent elements (all ranks).
  double held_off_branch() const;

  Reads in_;
  Changes out_;
  Operations op_;
};

}  // namespace ugs::mech
