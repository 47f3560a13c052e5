// Which MPI rank owns which mesh node (and so which rows of the stiffness matrix): PT-Scotch through
// PETSc's MatPartitioning on the node graph of the tetrahedra (default), or recursive coordinate
// bisection (rcb: cuts along the longest extent; for layered models it gives vertical cuts with
// small interfaces and costs nothing). Elements go to every rank owning one of their nodes.
#pragma once
#include <string>
#include <vector>

#include "ugs/mechanics/model.hpp"

namespace ugs::mech {

// Named "ptscotch" and "rcb" (ugs/driver/names.hpp).
enum class PartitionMethod { PtScotch, Rcb };

// Part (0 .. nparts-1) of each mesh node. Runs on one process (rank 0); deterministic.
std::vector<int> partition_nodes(const Model& model, const std::vector<Point3>& coords, int nparts, PartitionMethod method);

}  // namespace ugs::mech
