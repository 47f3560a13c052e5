// PETSc calls of the contact solver: a non-zero error code becomes a ugs::ComputeError through the
// mechanics library's handler (the same message format as every other PETSc call of ugs-solve).
#pragma once
#include <petscsys.h>

namespace ugs::mech {
[[noreturn]] void throw_petsc_error(PetscErrorCode code, const char* call, const char* file, int line);
}

#define UGS_CONTACT_PETSC(...)                                                                              \
  do {                                                                                                      \
    const PetscErrorCode ugs_contact_code_ = (__VA_ARGS__);                                                 \
    if (ugs_contact_code_) ::ugs::mech::throw_petsc_error(ugs_contact_code_, #__VA_ARGS__, __FILE__, __LINE__); \
  } while (0)
