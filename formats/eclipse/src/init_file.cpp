// INIT arrays through opm-common's EclIO (eclipse.hpp).
#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <opm/io/eclipse/EclFile.hpp>

#include "records.hpp"
#include "ugs/eclipse/eclipse.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::eclipse {
namespace fs = std::filesystem;

std::string default_egrid(const std::string& init_path) {
  const fs::path p(init_path);
  const std::string ext = p.extension().string();
  const bool lower = !ext.empty() && std::islower(static_cast<unsigned char>(ext.back()));
  const bool formatted = ext == ".FINIT" || ext == ".finit";
  std::string want = formatted ? ".FEGRID" : ".EGRID";
  if (lower)
    for (char& c : want) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string egrid = fs::path(p).replace_extension(want).string();
  std::error_code ec;
  return fs::is_regular_file(egrid, ec) ? egrid : "";
}

std::vector<double> read_init_array(const std::string& path, const std::string& keyword, const Grid& grid) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "no such file (expected the INIT file of the simulation, CASE.INIT)");
  std::vector<double> out;
  try {
    check_records(path);
    Opm::EclIO::EclFile f(path);
    const auto list = f.getList();
    int index = -1;
    std::set<std::string> names;
    for (std::size_t n = 0; n < list.size(); ++n) {
      const auto& [name, type, count] = list[n];
      names.insert(name);
      if (name == keyword && index < 0) index = static_cast<int>(n);
    }
    if (index < 0) {
      std::string have;
      for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
      throw InputError(path, fmt::format("no array {} (arrays: {})", keyword, have));
    }
    const auto type = std::get<1>(list[static_cast<std::size_t>(index)]);
    std::vector<double> v;
    using Opm::EclIO::eclArrType;
    if (type == eclArrType::REAL) {
      const auto& a = f.get<float>(index);
      v.assign(a.begin(), a.end());
    } else if (type == eclArrType::DOUB) {
      v = f.get<double>(index);
    } else if (type == eclArrType::INTE) {
      const auto& a = f.get<int>(index);
      v.assign(a.begin(), a.end());
    } else {
      throw InputError(path, fmt::format("array {} is not numeric", keyword));
    }
    if (v.size() == grid.num_active()) {
      out = std::move(v);
    } else if (v.size() == grid.active.size()) {
      out.reserve(grid.num_active());
      for (const auto g : grid.global) out.push_back(v[g]);
    } else {
      throw InputError(path, fmt::format("array {} has {} values; the grid {} has {} active of {} cells", keyword, v.size(), grid.path,
                                         grid.num_active(), grid.active.size()));
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what)
      if (!std::isprint(static_cast<unsigned char>(c))) c = ' ';
    throw InputError(path, fmt::format("cannot be read as an ECLIPSE INIT file: {}", what));
  }
  return out;
}

}  // namespace ugs::eclipse
