// PetscSession gives back what SuperLU_DIST's load-time mallopt took: memory freed returns to the
// system (without it a process's resident size only grows, and ugs-solve's peak is the sum of
// everything it ever held at once).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "ugs/mechanics/petsc_session.hpp"

namespace {

long resident_kb() {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

}  // namespace

TEST(PetscSession, MemoryFreedGoesBackToTheSystem) {
  ugs::mech::PetscSession session;
  constexpr std::size_t kBytes = 256u << 20;
  // Many arrays of 1 MB, as a matrix's rows or a gather's parts come, then all freed.
  std::vector<char*> parts;
  const long before = resident_kb();
  for (std::size_t done = 0; done < kBytes; done += 1u << 20) {
    char* p = static_cast<char*>(std::malloc(1u << 20));
    ASSERT_NE(p, nullptr);
    std::memset(p, 1, 1u << 20);
    parts.push_back(p);
  }
  const long held = resident_kb();
  EXPECT_GT(held - before, 200 * 1024);
  for (char* p : parts) std::free(p);
  const long after = resident_kb();
  EXPECT_LT(after - before, 16 * 1024) << "before " << before << " kB, holding " << held << " kB, after freeing " << after << " kB";
}
