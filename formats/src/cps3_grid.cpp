// CPS-3 ASCII grids (Petrel, Landmark): FS* header lines, "->" comment lines, then the values
// column by column from the west, each column from the north down. The header is checked against
// itself (FSLIMI against FSNROW and FSXINC) and against the count of values.
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "text_lines.hpp"
#include "ugs/formats/horizon_grid.hpp"

namespace ugs {

namespace {
constexpr long long max_nodes_per_axis = 10'000'000;
}

HorizonGrid read_cps3_grid(const std::string& path) {
  text::Lines in(path, "a CPS-3 ASCII grid");
  HorizonGrid g;
  g.path = in.name();
  g.format = "CPS-3 ASCII";

  std::optional<double> null;
  std::optional<std::array<double, 4>> limits;
  std::size_t limits_line = 0, inc_line = 0, nrow_line = 0;
  long long nrow = 0, ncol = 0;
  double xinc = 0, yinc = 0;
  bool first = true, data = false;
  while (!data && in.next()) {
    const auto& t = in.tokens();
    if (t.empty() || t[0].starts_with("->") || t[0].starts_with("!")) continue;
    double v;
    if (text::parse_number(t[0], v)) {
      data = true;
      break;
    }
    const std::string_view key = t[0];
    if (first && key != "FSASCI")
      throw in.error(fmt::format("'{}' is not a CPS-3 ASCII grid's first keyword (expected FSASCI)", text::shown(key)));
    first = false;
    auto need = [&](std::size_t k) {
      if (t.size() < k + 1) throw in.error(fmt::format("{} needs {} numbers, the line has {}", key, k, t.size() - 1));
    };
    if (key == "FSASCI") {
      need(1);
      null = text::number(in, t.back(), "FSASCI's undefined value (its last number)");
    } else if (key == "FSATTR") {
      // attributes of the grid's display: nothing for its geometry
    } else if (key == "FSLIMI") {
      need(4);
      limits = {text::number(in, t[1], "FSLIMI xmin"), text::number(in, t[2], "FSLIMI xmax"),
                text::number(in, t[3], "FSLIMI ymin"), text::number(in, t[4], "FSLIMI ymax")};
      limits_line = in.line();
    } else if (key == "FSNROW") {
      need(2);
      nrow = text::integer(in, t[1], "FSNROW rows", 2, max_nodes_per_axis);
      ncol = text::integer(in, t[2], "FSNROW columns", 2, max_nodes_per_axis);
      nrow_line = in.line();
    } else if (key == "FSXINC") {
      need(2);
      xinc = text::number(in, t[1], "FSXINC x increment");
      yinc = text::number(in, t[2], "FSXINC y increment");
      if (!(xinc > 0) || !(yinc > 0)) throw in.error(fmt::format("FSXINC {} {}: increments must be > 0", xinc, yinc));
      inc_line = in.line();
    } else {
      throw in.error(fmt::format("unknown CPS-3 header keyword '{}' (expected FSASCI, FSATTR, FSLIMI, FSNROW, FSXINC "
                                 "or a '->' comment)",
                                 text::shown(key)));
    }
  }
  if (first) throw InputError(fmt::format("{}:{}", in.name(), in.line()), "empty file (expected a CPS-3 ASCII grid)");
  const std::string where = fmt::format("{}:{}", in.name(), in.line());
  if (!limits) throw InputError(where, "no FSLIMI line before the values (expected FSLIMI xmin xmax ymin ymax zmin zmax)");
  if (!nrow) throw InputError(where, "no FSNROW line before the values (expected FSNROW rows columns)");
  if (!inc_line) throw InputError(where, "no FSXINC line before the values (expected FSXINC xinc yinc)");
  if (!null) null = 1e30;
  g.nx = static_cast<std::size_t>(ncol);
  g.ny = static_cast<std::size_t>(nrow);
  if (static_cast<double>(g.nx) * static_cast<double>(g.ny) > 5e8)
    throw InputError(fmt::format("{}:{}", in.name(), nrow_line),
                     fmt::format("FSNROW {} x {} nodes is more than 500 million", nrow, ncol));
  const auto [xmin, xmax, ymin, ymax] = *limits;
  g.x0 = xmin;
  g.y0 = ymin;
  g.dx = xinc;
  g.dy = yinc;
  // 1 % of a cell allows for the digits written.
  const double xspan = static_cast<double>(ncol - 1) * xinc, yspan = static_cast<double>(nrow - 1) * yinc;
  if (std::fabs(xmax - xmin - xspan) > 0.01 * xinc || std::fabs(ymax - ymin - yspan) > 0.01 * yinc)
    throw InputError(fmt::format("{}:{}", in.name(), limits_line),
                     fmt::format("FSLIMI {} {} {} {} disagrees with FSNROW {} {} and FSXINC {} {} (line {}): "
                                 "(columns - 1) x xinc = {}, (rows - 1) x yinc = {}",
                                 xmin, xmax, ymin, ymax, nrow, ncol, xinc, yinc, inc_line, xspan, yspan));

  // Values column by column from the west, each from the north (row ny - 1) down.
  const std::size_t n = g.nx * g.ny;
  g.z.assign(0, 0.0);
  std::size_t count = 0;
  std::vector<double> values;
  const double tol = 1e-6 * std::max(1.0, std::fabs(*null));
  auto take = [&](std::string_view t) {
    if (count == n)
      throw in.error(fmt::format("value {} '{}' is one more than FSNROW's {} x {} = {} (the header disagrees with the "
                                 "values)",
                                 n + 1, text::shown(t), nrow, ncol, n));
    double v = text::number(in, t, fmt::format("value {}", count + 1));
    if (std::fabs(v - *null) <= tol) {
      v = std::nan("");
      ++g.undefined;
    }
    values.push_back(v);
    ++count;
  };
  if (data) {
    for (const auto t : in.tokens()) take(t);
    while (in.next())
      for (const auto t : in.tokens()) take(t);
  }
  if (count != n)
    throw InputError(fmt::format("{}:{}", in.name(), in.line()),
                     fmt::format("the file ends after {} values, FSNROW {} x {} needs {} (the header disagrees with the "
                                 "values)",
                                 count, nrow, ncol, n));
  g.z.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = k / g.ny, j = g.ny - 1 - k % g.ny;
    g.z[j * g.nx + i] = values[k];
  }
  return g;
}

}  // namespace ugs
