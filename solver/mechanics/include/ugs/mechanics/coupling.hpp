// Extra unknowns solved with the displacement in MechanicsSolver's Newton iteration: the
// Lagrange multipliers of the fault contact (ugs_contact, thesis 3.5.2) are the one user. The
// solver keeps its element loop, tangent matrix, sub-stepping and load history; a coupling adds
// its forces to the residual, its own equations to the norm, and solves the enlarged (saddle-point)
// Newton system in place of the displacement-only one:
//
//   [ A  C ] [du]   [ r ]      r = f_ext - f_int(u) - (the coupling's forces), A the tangent
//   [ B  D ] [dl] = [-F ]      F the coupling's equations
//
// The calls are collective over the solver's communicator. PETSc objects are passed as handles.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <mpi.h>

#include "ugs/formats/mesh.hpp"

typedef struct _p_Mat* Mat;
typedef struct _p_Vec* Vec;

namespace ugs::mech {

// The distribution of the displacement unknowns (3 per node, block size 3): rank r owns global
// nodes [node_begin_of_rank[r], node_begin_of_rank[r+1]); matrix row 3 g + c is component c of
// global node g.
struct CouplingContext {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::int64_t n_global_nodes = 0;
  std::int64_t node_begin = 0;
  int n_owned = 0;
  std::vector<std::int64_t> node_begin_of_rank;      // size + 1 entries, every rank
  const std::vector<Point3>* owned_x = nullptr;      // coordinates of the owned nodes (first n_owned)
  const std::vector<std::uint8_t>* owned_fixed = nullptr;  // prescribed components (bits) of the owned nodes
  std::vector<std::int64_t> global_of_mesh_node;     // rank 0 only: global node of each mesh node
  Vec u = nullptr;                                    // the displacement (global form, ghosted)
};

struct CouplingSolve {
  int iterations = 0;
  bool ok = true;
  std::string failure;
};

class Coupling {
public:
  virtual ~Coupling() = default;
  // Once, after the model is distributed.
  virtual void setup(const CouplingContext& ctx) = 0;
  // A step starts (MechanicsSolver::advance); a (sub-)step covering `fraction` of it is tried.
  virtual void begin_step() = 0;
  virtual void begin_substep(double fraction) = 0;
  // Adds the coupling's forces to r (free rows only: r is zero on prescribed components) for the
  // displacement u, decides its active set, and returns the squared norm of its own equations [N^2].
  virtual double residual(Vec u, Vec r) = 0;
  // True when the last residual() changed no state of the active set.
  virtual bool settled() = 0;
  // Non-empty when the iteration cannot converge (e.g. a state cycles): why, naming the place.
  virtual std::string stalled() = 0;
  // Solves the Newton system with the displacement tangent A (prescribed rows and columns already
  // replaced by a diagonal) and the right-hand side r; writes du (zero on prescribed components)
  // and updates the coupling's own unknowns.
  virtual CouplingSolve solve(Mat A, Vec r, Vec du, double rtol) = 0;
  // Added to the message of a step that failed to converge.
  virtual std::string diagnosis() = 0;
  // The (sub-)step converged / is abandoned / the whole step is abandoned.
  virtual void commit() = 0;
  virtual void revert_substep() = 0;
  virtual void revert_step() = 0;
};

}  // namespace ugs::mech
