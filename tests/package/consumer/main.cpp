// Reads a mesh with the installed ugs library and prints its tetrahedron count.
#include <cstdio>

#include "ugs/formats/msh.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const ugs::Mesh m = ugs::read_msh(argv[1]);
  std::printf("%zu\n", m.count(ugs::ElementType::Tetrahedron));
  return 0;
}
