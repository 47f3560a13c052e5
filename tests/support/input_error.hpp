// The message of the ugs::InputError a call throws, for tests of bad input.
#pragma once
#include <functional>
#include <string>

#include "ugs/formats/error.hpp"

namespace ugs::test {

// e.what() of the InputError `f` throws; "(no InputError)" when it throws none.
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace ugs::test
