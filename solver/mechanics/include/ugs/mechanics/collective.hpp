// Errors under MPI: a bad input found by one rank (rank 0 reads the files) must stop every rank
// with the same message and exit code, never leave the others waiting in a collective call.
// collective() runs a piece of rank-local work, agrees on the outcome and rethrows the first
// failing rank's error (InputError or ComputeError, with its message) on every rank.
#pragma once
#include <functional>
#include <string>

#include <mpi.h>

namespace ugs::mech {

void collective(MPI_Comm comm, const std::function<void()>& work);

// Broadcasts a string from `root`.
void broadcast(MPI_Comm comm, std::string& s, int root = 0);

}  // namespace ugs::mech
