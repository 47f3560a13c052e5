// Every PETSc call of the mechanics goes through UGS_PETSC(...): a non-zero error code becomes a
// ugs::ComputeError naming the call, where it was made and PETSc's own message (PETSc's error
// handler is replaced so that nothing is printed or aborted behind our back).
#pragma once
#include <petscsys.h>

namespace ugs::mech {

// Makes PETSc return errors silently and remember the message; call once after PetscInitialize.
void install_petsc_error_handler();
[[noreturn]] void throw_petsc_error(PetscErrorCode code, const char* call, const char* file, int line);

}  // namespace ugs::mech

#define UGS_PETSC(...)                                                                     \
  do {                                                                                     \
    const PetscErrorCode ugs_petsc_code_ = (__VA_ARGS__);                                  \
    if (ugs_petsc_code_) ::ugs::mech::throw_petsc_error(ugs_petsc_code_, #__VA_ARGS__, __FILE__, __LINE__); \
  } while (0)
