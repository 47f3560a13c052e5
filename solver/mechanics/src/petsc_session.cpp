#include "ugs/mechanics/petsc_session.hpp"

#include <petscsys.h>

#include "petsc_check.hpp"

namespace ugs::mech {

PetscSession::PetscSession(const std::vector<std::string>& options) {
  storage_.push_back("ugs-solve");
  storage_.insert(storage_.end(), options.begin(), options.end());
  for (auto& s : storage_) argv_.push_back(s.data());
  argv_.push_back(nullptr);
  int argc = static_cast<int>(storage_.size());
  char** argv = argv_.data();
  // PETSc prints nothing of its own here: no help banner, errors through our handler.
  UGS_PETSC(PetscInitialize(&argc, &argv, nullptr, nullptr));
  install_petsc_error_handler();
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
  MPI_Comm_size(PETSC_COMM_WORLD, &size_);
}

PetscSession::~PetscSession() { PetscFinalize(); }

bool petsc_option_given(const char* name) {
  PetscBool has = PETSC_FALSE;
  UGS_PETSC(PetscOptionsHasName(nullptr, nullptr, name, &has));
  return has == PETSC_TRUE;
}

}  // namespace ugs::mech
