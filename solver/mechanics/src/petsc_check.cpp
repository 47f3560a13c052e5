#include "petsc_check.hpp"

#include <cstring>
#include <string>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::mech {
namespace {

thread_local std::string g_message;

PetscErrorCode record_error(MPI_Comm, int line, const char* fun, const char* file, PetscErrorCode n, PetscErrorType p,
                            const char* mess, void*) {
  if (p == PETSC_ERROR_INITIAL) {
    const char* base = file ? std::strrchr(file, '/') : nullptr;
    g_message = fmt::format("{} ({} at {}:{})", mess && *mess ? mess : "", fun ? fun : "?", base ? base + 1 : (file ? file : "?"), line);
  }
  return n;
}

}  // namespace

void install_petsc_error_handler() { PetscPushErrorHandler(record_error, nullptr); }

void throw_petsc_error(PetscErrorCode code, const char* call, const char* file, int line) {
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  const char* base = std::strrchr(file, '/');
  std::string call_name(call);
  if (auto p = call_name.find('('); p != std::string::npos) call_name.resize(p);
  std::string msg = fmt::format("PETSc error {} in {} ({}:{}): {}", static_cast<int>(code), call_name, base ? base + 1 : file,
                                line, text ? text : "");
  if (!g_message.empty()) msg += "; " + g_message;
  for (auto& c : msg)
    if (c == '\n') c = ' ';
  g_message.clear();
  throw ComputeError(msg);
}

}  // namespace ugs::mech
