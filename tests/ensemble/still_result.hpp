// The result a stand-in solver copies to {out}: u = 0 on every node at each date, so that the
// members' surface metrics are 0 and the test's subject is what the stand-in writes beside it.
#pragma once
#include <string>
#include <vector>

#include "ugs/formats/fields.hpp"

namespace ugs::test {

inline void write_still_result(const std::string& path, const Mesh& m, const std::vector<std::string>& dates) {
  FieldSeriesWriter w(path, m);
  for (const std::string& date : dates) {
    const Field u{"u", 3, std::vector<double>(3 * m.num_nodes(), 0.0)};
    const Field nf[] = {u};
    w.add_step(date, double(*parse_iso_date(date)), nf);
  }
  w.commit();
}

}  // namespace ugs::test
