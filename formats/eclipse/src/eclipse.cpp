// ECLIPSE binary output through opm-common's EclIO (see eclipse.hpp and docs/eclipse.md).
#include "ugs/eclipse/eclipse.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>

#include <fmt/format.h>
#include <opm/io/eclipse/EGrid.hpp>
#include <opm/io/eclipse/EclFile.hpp>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "records.hpp"

namespace ugs::eclipse {
namespace fs = std::filesystem;
namespace {

double length_unit_m(const std::string& unit, const std::string& where) { return grid_length_unit_m(unit, where); }

// Runs an EclIO call; whatever it throws (missing file, "tail not matching header" of a truncated
// file, an array of an unexpected type) becomes an InputError naming the file.
template <class F>
auto eclio(const std::string& path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::string what = e.what();
    // EclIO prefixes its source position: "[./src/opm/io/eclipse/EclFile.cpp:630] ..."
    if (!what.empty() && what.front() == '[') {
      const auto close = what.find("] ");
      if (close != std::string::npos) what.erase(0, close + 2);
    }
    // One line, and printable: the message may quote bytes of a damaged file.
    for (char& c : what)
      if (!std::isprint(static_cast<unsigned char>(c))) c = c == '\n' ? ' ' : '?';
    throw InputError(path, fmt::format("cannot be read as ECLIPSE {} output: {}", is_formatted(path) ? "formatted" : "binary", what));
  }
}

// EGrid's constructor indexes the small arrays that say which grid an array belongs to (LGR,
// NNCHEAD, GRIDHEAD, MAPUNITS) without checking their sizes, and takes the last of two COORD (ZCORN,
// ACTNUM, ...) arrays of one grid: walk the arrays as it does and refuse what it would misread.
// Returns the global grid's dimensions (GRIDHEAD items 2-4), checked.
std::array<int, 3> check_egrid_arrays(Opm::EclIO::EclFile& f, const std::string& path) {
  using Opm::EclIO::eclArrType;
  const auto list = f.getList();
  std::string grid = "global";
  std::vector<std::string> lgrs;
  std::map<std::string, int> seen;
  std::array<int, 3> dims{0, 0, 0};
  for (std::size_t n = 0; n < list.size(); ++n) {
    const auto& [name, type, count] = list[n];
    const auto need = [&](bool type_ok, std::int64_t min_items, const char* expected) {
      if (!type_ok || count < min_items)
        throw InputError(path, fmt::format("array {} (number {}) has {} items of another type or fewer than expected ({})", name,
                                           n + 1, count, expected));
      f.loadData(static_cast<int>(n));
    };
    const bool text = type == eclArrType::CHAR || type == eclArrType::C0NN;
    if (name == "ENDLGR") grid = "global";
    if (name == "LGR") {
      need(text, 1, "the name of a local grid");
      lgrs.push_back(f.get<std::string>(static_cast<int>(n))[0]);
      grid = lgrs.back();
    } else if (name == "NNCHEAD") {
      need(type == eclArrType::INTE, 2, "at least 2 integers");
      const int g = f.get<int>(static_cast<int>(n))[1];
      if (g < 0 || g > static_cast<int>(lgrs.size()))
        throw InputError(path, fmt::format("NNCHEAD (array number {}) names local grid {}, but {} are defined before it", n + 1, g,
                                           lgrs.size()));
      grid = g == 0 ? "global" : lgrs[static_cast<std::size_t>(g - 1)];
    } else if (name == "MAPUNITS") {
      need(text, 1, "a unit name");
    } else if (name == "GRIDHEAD") {
      need(type == eclArrType::INTE, 4, "at least 4 integers");
    }
    static const char* const per_grid[] = {"GRIDHEAD", "COORD", "ZCORN", "ACTNUM", "NNC1", "NNC2", "HOSTNUM"};
    if (grid != "global" || std::find(std::begin(per_grid), std::end(per_grid), name) == std::end(per_grid)) continue;
    if (++seen[name] > 1) throw InputError(path, fmt::format("a second {} array in the global grid (array number {})", name, n + 1));
    if (name == "GRIDHEAD") {
      const auto& h = f.get<int>(static_cast<int>(n));
      dims = {h[1], h[2], h[3]};
      if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0 || static_cast<double>(dims[0]) * dims[1] * dims[2] > 2.0e9)
        throw InputError(path, fmt::format("grid dimensions {} x {} x {} (expected positive, at most 2e9 cells)", dims[0], dims[1],
                                           dims[2]));
    }
  }
  if (!seen.count("GRIDHEAD")) throw InputError(path, "no GRIDHEAD array for the global grid (expected an EGRID file)");
  return dims;
}

}  // namespace

Grid read_egrid(const std::string& path, const Point3& offset) {
  if (!fs::exists(path)) throw InputError(path, "no such file (expected the EGRID of the simulation, CASE.EGRID)");
  Grid grid;
  grid.path = path;
  eclio(path, [&] {
    check_records(path);
    std::array<int, 3> n;
    {
      Opm::EclIO::EclFile arrays(path);
      n = check_egrid_arrays(arrays, path);
    }
    Opm::EclIO::EGrid eg(path);
    if (eg.is_radial()) throw InputError(path, "radial grid (only Cartesian corner-point grids are imported)");
    if (eg.dimension() != n) throw InputError(path, "the global grid's dimensions differ between GRIDHEAD and EclIO");
    grid.dims = n;
    const std::size_t total = static_cast<std::size_t>(n[0]) * n[1] * n[2];
    // EclIO indexes COORD, ZCORN and ACTNUM without checking their sizes: check them here.
    std::map<std::string, std::int64_t> size;
    for (const auto& [name, type, count] : eg.getList())
      if (!size.count(name)) size[name] = count;
    const auto expect = [&](const std::string& name, std::size_t want, bool required) {
      if (!size.count(name)) {
        if (required) throw InputError(path, fmt::format("no {} array (expected a corner-point grid)", name));
        return;
      }
      if (static_cast<std::size_t>(size[name]) != want)
        throw InputError(path, fmt::format("{} has {} values, expected {} for a {} x {} x {} grid", name, size[name], want, n[0], n[1], n[2]));
    };
    if (size.count("COORDSYS")) throw InputError(path, "COORDSYS (several reservoirs in one grid) is not supported");
    expect("COORD", 6 * static_cast<std::size_t>(n[0] + 1) * static_cast<std::size_t>(n[1] + 1), true);
    expect("ZCORN", 8 * total, true);
    expect("ACTNUM", total, false);
    grid.active.assign(total, -1);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const int a = eg.active_index(i, j, k);
          if (a < 0) continue;
          const std::size_t g = static_cast<std::size_t>(i) + static_cast<std::size_t>(n[0]) * (j + static_cast<std::size_t>(n[1]) * k);
          if (static_cast<std::size_t>(a) != grid.global.size())
            throw InputError(path, fmt::format("active cell ({},{},{}) has active index {}, expected {}", i + 1, j + 1, k + 1, a,
                                               grid.global.size()));
          grid.active[g] = a;
          grid.global.push_back(static_cast<std::uint32_t>(g));
        }
    if (grid.global.size() != static_cast<std::size_t>(eg.activeCells()))
      throw InputError(path, fmt::format("{} active cells in ACTNUM, {} in GRIDHEAD", grid.global.size(), eg.activeCells()));
    if (grid.global.empty()) throw InputError(path, "no active cell (ACTNUM is all 0)");

    grid.length_unit = "METRES";
    if (eg.hasKey("GRIDUNIT")) {
      const auto& gu = eg.get<std::string>("GRIDUNIT");
      if (!gu.empty()) grid.length_unit = grid_unit_name(gu[0]);
    }
    const double L = length_unit_m(grid.length_unit, path + ": GRIDUNIT");
    // MAPAXES: Y-axis point, origin, X-axis point, in MAPUNITS (else the grid's unit); float32 in
    // the file, used in double from here on.
    // Read from the records themselves: EGrid::get_mapaxes() is converted by MAPUNITS in some
    // opm-common versions and not in others.
    MapAxes axes;
    if (eg.hasKey("MAPAXES")) {
      const std::vector<float> ma = eg.get<float>("MAPAXES");
      if (ma.size() != 6) throw InputError(path, fmt::format("MAPAXES has {} values (expected 6)", ma.size()));
      std::string mu;
      if (eg.hasKey("MAPUNITS")) {
        const auto& v = eg.get<std::string>("MAPUNITS");
        if (!v.empty()) mu = grid_unit_name(v[0]);
      }
      const double M = mu.empty() ? L : length_unit_m(mu, path + ": MAPUNITS");
      std::array<double, 6> p;
      for (int q = 0; q < 6; ++q) p[q] = static_cast<double>(ma[q]) * M;
      axes = map_axes(p, path);
      grid.mapaxes = true;
    }
    if (eg.hasKey("NNC1")) grid.nnc = eg.get<int>("NNC1").size();

    grid.corners.resize(grid.global.size());
    std::array<double, 8> X, Y, Z;
    for (std::size_t a = 0; a < grid.global.size(); ++a) {
      eg.getCellCorners(static_cast<int>(grid.global[a]), X, Y, Z);
      for (int c = 0; c < 8; ++c) {
        const double x = X[c] * L, y = Y[c] * L, depth = Z[c] * L;
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(depth)) {
          const auto ijk = grid.ijk(grid.global[a]);
          throw InputError(path, fmt::format("cell ({},{},{}): corner {} is not finite", ijk[0] + 1, ijk[1] + 1, ijk[2] + 1, c + 1));
        }
        grid.corners[a][c] = axes.to_mesh(x, y, depth, offset);
      }
    }
  });
  return grid;
}

double pressure_unit_pa(int units, const std::string& where) {
  switch (units) {
    case 1: return 1.0e5;             // METRIC: bar
    case 2: return 6894.757293168361; // FIELD: psi
    case 3:                           // LAB: atm
    case 4: return 101325.0;          // PVT-M: atm
    default:
      throw InputError(where, fmt::format("unit system {} in INTEHEAD item 3 (expected 1 METRIC, 2 FIELD, 3 LAB or 4 PVT-M)", units));
  }
}

std::string default_restart(const std::string& egrid_path) {
  fs::path p(egrid_path);
  const bool lower = !p.extension().string().empty() && std::islower(static_cast<unsigned char>(p.extension().string().back()));
  auto with = [&](std::string ext) {
    if (lower)
      for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return fs::path(p).replace_extension(ext).string();
  };
  for (const char* ext : {".UNRST", ".FUNRST", ".X0000", ".F0000"})
    if (fs::exists(with(ext))) return with(ext);
  return "";
}

struct Restart::Impl {
  std::string path;
  struct Source {
    std::string file;
    std::unique_ptr<Opm::EclIO::EclFile> ecl;
  };
  std::vector<Source> sources;
  struct Step {
    std::size_t source;
    int pressure_index;
    std::int64_t size;
    int nx, ny, nz, nactive;
  };
  std::vector<Step> where;
  std::vector<RestartStep> steps;
};

Restart::Restart(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  // Non-unified: CASE.X0001 (binary) or CASE.F0001 (formatted); every numbered sibling is a step.
  static const std::regex separate(R"(\.([XxFf])([0-9]{4})$)");
  std::smatch m;
  const std::string name = fs::path(path).filename().string();
  std::vector<std::pair<int, std::string>> files;
  if (std::regex_search(name, m, separate)) {
    const std::string stem = name.substr(0, static_cast<std::size_t>(m.position(0)));
    const char kind = m[1].str()[0];
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    if (!fs::exists(path)) throw InputError(path, "no such file (expected a restart file of the simulation)");
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string f = e.path().filename().string();
      std::smatch fm;
      if (f.size() == stem.size() + 6 && f.compare(0, stem.size(), stem) == 0 && std::regex_search(f, fm, separate) &&
          fm[1].str()[0] == kind)
        files.emplace_back(std::stoi(fm[2].str()), (dir / f).string());
    }
    std::sort(files.begin(), files.end());
  } else {
    if (!fs::exists(path)) throw InputError(path, "no such file (expected the restart of the simulation, CASE.UNRST)");
    files.emplace_back(-1, path);
  }
  for (const auto& [number, file] : files) {
    auto ecl = eclio(file, [&] {
      check_records(file);
      return std::make_unique<Opm::EclIO::EclFile>(file);
    });
    const auto names = ecl->arrayNames();
    // Step starts: each SEQNUM (unified), or the whole file (non-unified).
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == "SEQNUM") starts.push_back(i);
    if (number >= 0 && starts.empty()) starts.push_back(0);
    if (starts.empty()) throw InputError(file, "no SEQNUM record: not a unified restart file (CASE.UNRST)");
    const auto list = ecl->getList();
    for (std::size_t s = 0; s < starts.size(); ++s) {
      const std::size_t end = s + 1 < starts.size() ? starts[s + 1] : names.size();
      int report = number, ih = -1, pr = -1;
      for (std::size_t i = starts[s]; i < end && names[i] != "LGR"; ++i) {
        if (names[i] == "SEQNUM") {
          const auto& v = eclio(file, [&]() -> const std::vector<int>& {
            ecl->loadData(static_cast<int>(i));
            return ecl->get<int>(static_cast<int>(i));
          });
          if (v.empty()) throw InputError(file, "empty SEQNUM record");
          report = v[0];
        } else if (names[i] == "INTEHEAD" && ih < 0) {
          ih = static_cast<int>(i);
        } else if (names[i] == "PRESSURE" && pr < 0) {
          pr = static_cast<int>(i);
        }
      }
      const std::string where = fmt::format("{}: report step {}", file, report);
      if (ih < 0) throw InputError(where, "no INTEHEAD record");
      const auto& h = eclio(file, [&]() -> const std::vector<int>& {
        ecl->loadData(ih);
        return ecl->get<int>(ih);
      });
      if (h.size() < 67) throw InputError(where, fmt::format("INTEHEAD has {} items (expected at least 67)", h.size()));
      const int day = h[64], month = h[65], year = h[66];
      const std::string date = fmt::format("{:04d}-{:02d}-{:02d}", year, month, day);
      const auto t = year >= 1 && year <= 9999 && month >= 1 && month <= 12 && day >= 1 && day <= 31 ? parse_iso_date(date)
                                                                                                     : std::nullopt;
      if (!t) throw InputError(where, fmt::format("INTEHEAD date day {} month {} year {} is not a date (items 65-67)", day, month, year));
      if (pr < 0) throw InputError(where, "no PRESSURE array (the restart must hold the pressure: RPTRST BASIC=2)");
      const auto type = std::get<1>(list[static_cast<std::size_t>(pr)]);
      if (type != Opm::EclIO::REAL && type != Opm::EclIO::DOUB) throw InputError(where, "PRESSURE is not a REAL or DOUB array");
      pressure_unit_pa(h[2], where + ": INTEHEAD item 3");
      if (!impl_->steps.empty()) {
        const auto& last = impl_->steps.back();
        if (!(*t > last.time))
          throw InputError(where, fmt::format("date {} is not after the previous report step's {} (report steps less than a day "
                                              "apart cannot be told apart)", date, last.date));
      }
      impl_->steps.push_back({report, date, *t, h[2]});
      impl_->where.push_back({impl_->sources.size(), pr, std::get<2>(list[static_cast<std::size_t>(pr)]), h[8], h[9], h[10], h[11]});
    }
    ecl->clearData();
    impl_->sources.push_back({file, std::move(ecl)});
  }
  if (impl_->steps.empty()) throw InputError(path, "no report step");
}

Restart::~Restart() = default;

const std::string& Restart::path() const { return impl_->path; }
const std::vector<RestartStep>& Restart::steps() const { return impl_->steps; }

void Restart::check_grid(const Grid& grid) const {
  for (std::size_t s = 0; s < impl_->steps.size(); ++s) {
    const auto& w = impl_->where[s];
    const std::string where = fmt::format("{}: report step {}", impl_->sources[w.source].file, impl_->steps[s].report);
    if (w.nx != grid.dims[0] || w.ny != grid.dims[1] || w.nz != grid.dims[2])
      throw InputError(where, fmt::format("grid {} x {} x {}, but {} is {} x {} x {}: the restart of another grid", w.nx, w.ny, w.nz,
                                          grid.path, grid.dims[0], grid.dims[1], grid.dims[2]));
    if (static_cast<std::size_t>(w.size) != grid.num_active())
      throw InputError(where, fmt::format("PRESSURE has {} values, but {} has {} active cells: the restart of another grid", w.size,
                                          grid.path, grid.num_active()));
  }
}

std::vector<double> Restart::pressure(std::size_t s) {
  if (s >= impl_->steps.size()) throw std::out_of_range("Restart::pressure: step index");
  const auto& w = impl_->where[s];
  auto& src = impl_->sources[w.source];
  const std::string where = fmt::format("{}: report step {}", src.file, impl_->steps[s].report);
  const double unit = pressure_unit_pa(impl_->steps[s].units, where);
  std::vector<double> p;
  eclio(src.file, [&] {
    src.ecl->loadData(w.pressure_index);
    const auto type = std::get<1>(src.ecl->getList()[static_cast<std::size_t>(w.pressure_index)]);
    if (type == Opm::EclIO::REAL) {
      const auto& v = src.ecl->get<float>(w.pressure_index);
      p.assign(v.begin(), v.end());
    } else {
      p = src.ecl->get<double>(w.pressure_index);
    }
    src.ecl->clearData();
  });
  if (static_cast<std::int64_t>(p.size()) != w.size)
    throw InputError(where, fmt::format("PRESSURE read {} values of {}", p.size(), w.size));
  for (std::size_t a = 0; a < p.size(); ++a) {
    if (!std::isfinite(p[a])) throw InputError(where, fmt::format("PRESSURE of active cell {} is not finite", a + 1));
    p[a] *= unit;
  }
  return p;
}

}  // namespace ugs::eclipse
