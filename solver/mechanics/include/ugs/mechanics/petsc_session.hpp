// PETSc (and MPI) for the lifetime of a tool or test: initialises with the PETSc options given
// (argv after "--" on the ugs-solve command line; -log_view and every -ksp_/-pc_ option work),
// installs the error handler that turns PETSc errors into ugs::ComputeError, finalises at the end.
// Restores glibc malloc's defaults that a library loaded with PETSc turned off (petsc_session.cpp),
// so that memory freed is returned to the system.
#pragma once
#include <string>
#include <vector>

namespace ugs::mech {

class PetscSession {
public:
  // `options` are PETSc command-line options, e.g. {"-pc_type", "hypre", "-log_view"}.
  explicit PetscSession(const std::vector<std::string>& options = {});
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

private:
  int rank_ = 0, size_ = 1;
  std::vector<std::string> storage_;
  std::vector<char*> argv_;
};

// Whether PETSc's options database holds `name` (a flag such as "-ugs_newton_monitor", given after
// "--"). PETSc must be initialised.
bool petsc_option_given(const char* name);

}  // namespace ugs::mech
