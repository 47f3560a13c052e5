#pragma once
// Two independent parts of one computation on the machine's two cores: `there` on a second thread
// while `here` runs on this one. The parts must touch disjoint data and be split in a fixed way by
// the caller, so that nothing depends on which finishes first.
#include <exception>
#include <thread>
#include <utility>

namespace ugs {

// Runs there() on a new thread and here() on this one, joins in every case, then rethrows here()'s
// exception if it threw, else there()'s.
template <class There, class Here>
void run_beside(There&& there, Here&& here) {
  std::exception_ptr failed;
  std::thread other([&] {
    try {
      there();
    } catch (...) {
      failed = std::current_exception();
    }
  });
  try {
    here();
  } catch (...) {
    other.join();
    throw;
  }
  other.join();
  if (failed) std::rethrow_exception(failed);
}

}  // namespace ugs
