// Shared helpers of the ugs-solve tool tests: the case generator, the tool under mpirun, and
// reading results back.
#pragma once
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "run_tool.hpp"
#include "ugs/formats/fields.hpp"

namespace ugs::test {

inline std::string make_case() { return std::string(UGS_BINARY_DIR) + "/tests/mechanics/mech_make_case"; }

// ugs-solve on n processes (n = 0: without mpirun). We run as root in CI: OpenMPI needs consent.
inline std::string solve_cmd(int n = 0) {
  const std::string s = tool("ugs-solve");
  if (n == 0) return s;
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -n " +
         std::to_string(n) + " --oversubscribe " + s;
}

// The last step's field of a results file.
inline std::vector<double> last_field(const std::string& h5, const std::string& name, bool cell) {
  FieldSeriesReader r(h5);
  const std::size_t s = r.steps().size() - 1;
  return (cell ? r.cell_field(s, name) : r.node_field(s, name)).values;
}

inline double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

inline double max_rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return a.size() == b.size() ? d / std::max(max_abs(a), 1e-300) : INFINITY;
}

}  // namespace ugs::test
