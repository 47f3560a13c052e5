// main() of a GoogleTest program that also runs under mpirun: PETSc (and MPI) set up for the
// tests, the results printed by rank 0 only; every rank's failures still fail the run (its exit
// code). Use: int main(int argc, char** argv) { return ugs::test::run_mpi_gtests(argc, argv); }
#pragma once

#include <mpi.h>

#include <gtest/gtest.h>

#include "ugs/mechanics/petsc_session.hpp"

namespace ugs::test {

inline int run_mpi_gtests(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
  if (rank != 0) delete listeners.Release(listeners.default_result_printer());
  return RUN_ALL_TESTS();
}

}  // namespace ugs::test
