// Test support: run a command through the shell and capture its exit code, stdout and stderr,
// and build small meshes by hand.
#pragma once
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ugs/formats/mesh.hpp"

namespace ugs::test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void spit(const std::filesystem::path& p, const std::string& data) {
  std::ofstream f(p, std::ios::binary);
  f << data;
}

// A fresh, empty temporary directory per call.
inline std::filesystem::path temp_dir(const std::string& tag) {
  auto d = std::filesystem::temp_directory_path() / ("ugs-test-" + tag + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// A fresh temporary folder for one test's case files, removed when the test ends (kept when
// UGS_TEST_KEEP is set, to look at); `dir / "case.toml"` is a file's path in it.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag) : path(temp_dir(tag)) {}
  ~TempDir() {
    if (!std::getenv("UGS_TEST_KEEP")) std::filesystem::remove_all(path);
  }
  std::string operator/(const std::string& f) const { return (path / f).string(); }
};

inline RunResult run(const std::string& command) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path();
  const auto o = dir / ("ugs-run-" + std::to_string(::getpid()) + "-" + std::to_string(counter) + ".out");
  const auto e = dir / ("ugs-run-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".err");
  const std::string full = "(" + command + ") >" + o.string() + " 2>" + e.string();
  const int status = std::system(full.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(o);
  r.err = slurp(e);
  std::filesystem::remove(o);
  std::filesystem::remove(e);
  return r;
}

inline std::string tool(const std::string& name) { return std::string(UGS_BINARY_DIR) + "/tools/" + name + "/" + name; }

// Unit cube [0,1]^3 split into 6 tetrahedra (Kuhn), with a top boundary group and a material.
inline Mesh unit_cube_mesh() {
  Mesh m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) m.add_node({double(i), double(j), double(k)});
  auto id = [](int i, int j, int k) { return static_cast<std::uint32_t>(i + 2 * j + 4 * k); };
  const int vol = m.entity_for_physical(3, "mat:rock");
  auto& tets = m.block(3, vol, ElementType::Tetrahedron);
  // Kuhn triangulation: paths from (0,0,0) to (1,1,1) along the axes in every order.
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms) {
    int c[3] = {0, 0, 0};
    std::uint32_t n[4];
    n[0] = id(0, 0, 0);
    for (int s = 0; s < 3; ++s) {
      c[p[s]] = 1;
      n[s + 1] = id(c[0], c[1], c[2]);
    }
    if (tet_signed_volume(m.nodes[n[0]], m.nodes[n[1]], m.nodes[n[2]], m.nodes[n[3]]) < 0) std::swap(n[2], n[3]);
    m.add_element(tets, n);
  }
  const int top = m.entity_for_physical(2, "bnd:top");
  auto& tri = m.block(2, top, ElementType::Triangle);
  const std::uint32_t t1[3] = {id(0, 0, 1), id(1, 0, 1), id(1, 1, 1)};
  const std::uint32_t t2[3] = {id(0, 0, 1), id(1, 1, 1), id(0, 1, 1)};
  m.add_element(tri, t1);
  m.add_element(tri, t2);
  m.update_entity_bboxes();
  m.provenance.push_back("unit_cube_mesh (test)");
  return m;
}

}  // namespace ugs::test
