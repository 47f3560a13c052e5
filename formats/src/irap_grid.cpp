// IRAP classic ASCII grids (RMS, Petrel): the 19-number header, then NX * NY values x fastest.
// The header is checked against itself (XMAX, YMAX against the increments of an unrotated grid)
// and against the values (their count): a grid whose header disagrees with its values is refused.
#include <cmath>

#include <fmt/format.h>

#include "text_lines.hpp"
#include "ugs/formats/horizon_grid.hpp"

namespace ugs {

namespace {

constexpr long long max_nodes_per_axis = 10'000'000;
constexpr double irap_undefined_above = 9999000.0;  // the undefined value is 9999900

}  // namespace

HorizonGrid read_irap_grid(const std::string& path) {
  text::Lines in(path, "an IRAP classic ASCII grid");
  HorizonGrid g;
  g.path = in.name();
  g.format = "IRAP classic ASCII";

  // The header: 19 numbers (normally 4 + 4 + 4 + 7 on four lines), told apart by position.
  static const char* names[19] = {"the format code",  "NY",   "XINC", "YINC", "XORI", "XMAX", "YORI",
                                  "YMAX",             "NX",   "ROTATION", "XROT", "YROT", "header number 13",
                                  "header number 14", "header number 15", "header number 16",
                                  "header number 17", "header number 18", "header number 19"};
  double h[19];
  std::size_t hline[19];
  std::size_t k = 0;
  std::size_t start = 0;  // first token of the current line that is not header
  while (k < 19) {
    if (!in.next())
      throw InputError(fmt::format("{}:{}", in.name(), in.line()),
                       fmt::format("the file ends inside the header after {} of its 19 numbers (expected -996 NY XINC "
                                   "YINC / XORI XMAX YORI YMAX / NX ROTATION XROT YROT / 0 0 0 0 0 0 0)",
                                   k));
    start = 0;
    for (const auto t : in.tokens()) {
      if (k == 19) break;
      if (k == 0 && t != "-996")
        throw in.error(fmt::format("'{}' is not an IRAP classic ASCII grid's first number (expected -996)", text::shown(t)));
      if (k == 1) h[k] = static_cast<double>(text::integer(in, t, "NY", 2, max_nodes_per_axis));
      else if (k == 8) h[k] = static_cast<double>(text::integer(in, t, "NX", 2, max_nodes_per_axis));
      else h[k] = text::number(in, t, names[k]);
      hline[k] = in.line();
      ++k;
      ++start;
    }
  }
  const std::string header_at = fmt::format("{}:{}", in.name(), hline[1]);
  g.ny = static_cast<std::size_t>(h[1]);
  g.dx = h[2];
  g.dy = h[3];
  g.x0 = h[4];
  g.y0 = h[6];
  g.nx = static_cast<std::size_t>(h[8]);
  g.rotation_deg = h[9];
  if (!(g.dx > 0)) throw InputError(header_at, fmt::format("XINC {} must be > 0", g.dx));
  if (g.dy == 0) throw InputError(header_at, "YINC must not be 0");
  if (std::fabs(g.rotation_deg) > 360)
    throw InputError(fmt::format("{}:{}", in.name(), hline[9]),
                     fmt::format("ROTATION {} is not an angle in degrees from -360 to 360", g.rotation_deg));
  if (static_cast<double>(g.nx) * static_cast<double>(g.ny) > 5e8)
    throw InputError(fmt::format("{}:{}", in.name(), hline[8]),
                     fmt::format("NX x NY = {} x {} nodes is more than 500 million", g.nx, g.ny));
  // An unrotated grid's extent follows from its increments; 1 % of a cell allows for the digits
  // written. (Writers differ on what XMAX holds for a rotated grid, so it is not checked there.)
  if (g.rotation_deg == 0) {
    const double xmax = g.x0 + static_cast<double>(g.nx - 1) * g.dx;
    if (std::fabs(xmax - h[5]) > 0.01 * g.dx)
      throw InputError(fmt::format("{}:{}", in.name(), hline[5]),
                       fmt::format("XMAX {} disagrees with XORI + (NX - 1) XINC = {} + {} x {} = {}", h[5], g.x0,
                                   g.nx - 1, g.dx, xmax));
    const double ymax = g.y0 + static_cast<double>(g.ny - 1) * g.dy;
    if (g.dy > 0 && std::fabs(ymax - h[7]) > 0.01 * g.dy)
      throw InputError(fmt::format("{}:{}", in.name(), hline[7]),
                       fmt::format("YMAX {} disagrees with YORI + (NY - 1) YINC = {} + {} x {} = {}", h[7], g.y0,
                                   g.ny - 1, g.dy, ymax));
  } else {
    const double tol = 1e-3 * std::min(g.dx, std::fabs(g.dy));
    if (std::fabs(h[10] - g.x0) > tol || std::fabs(h[11] - g.y0) > tol)
      throw InputError(fmt::format("{}:{}", in.name(), hline[10]),
                       fmt::format("the grid is rotated about ({}, {}), not about its origin ({}, {}) (expected XROT "
                                   "= XORI, YROT = YORI)",
                                   h[10], h[11], g.x0, g.y0));
  }

  // The values: exactly NX * NY of them.
  const std::size_t n = g.nx * g.ny;
  auto take = [&](std::string_view t) {
    if (g.z.size() == n)
      throw in.error(fmt::format("value {} '{}' is one more than the header's NX x NY = {} x {} = {} (the header "
                                 "disagrees with the values)",
                                 n + 1, text::shown(t), g.nx, g.ny, n));
    double v = text::number(in, t, fmt::format("value {}", g.z.size() + 1));
    if (v > irap_undefined_above) {
      v = std::nan("");
      ++g.undefined;
    }
    g.z.push_back(v);
  };
  for (std::size_t i = start; i < in.tokens().size(); ++i) take(in.tokens()[i]);
  while (in.next())
    for (const auto t : in.tokens()) take(t);
  if (g.z.size() != n)
    throw InputError(fmt::format("{}:{}", in.name(), in.line()),
                     fmt::format("the file ends after {} values, the header's NX x NY = {} x {} needs {} (the header "
                                 "disagrees with the values)",
                                 g.z.size(), g.nx, g.ny, n));
  return g;
}

}  // namespace ugs
