#include "ugs/mechanics/petsc_session.hpp"

#include <malloc.h>
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
  // SuperLU_DIST (linked by PETSc) turns off mmap and trimming in glibc's malloc when it is loaded
  // (mallopt M_MMAP_MAX = 0, M_TRIM_THRESHOLD = -1): memory freed is only reused, never returned, so
  // a process stays at its high-water mark. glibc's defaults again: large arrays freed after the
  // assembly or an output gather go back to the system.
  mallopt(M_MMAP_MAX, 65536);
  mallopt(M_TRIM_THRESHOLD, 128 * 1024);
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
