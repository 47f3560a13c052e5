// The sources of material fields (docs/case-file.md, "Properties that vary in space"), each read
// once and sampled at tetrahedra: a value per site, or none where the source does not cover it.
// Values are the source's own (before the field's scale and unit).
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

// A tetrahedron as the sources see it: its centroid and its element tag.
struct FieldSite {
  Point3 centroid{};
  std::uint64_t tag = 0;
};

struct Sampled {
  std::vector<double> value;  // per site
  std::vector<char> covered;  // per site: 0 where the source has no value there
};

// Depth table: linear between rows at the site's elevation (by_depth: at surface_elevation - z);
// covered between the first and the last row (inclusive).
Sampled sample_table(const MaterialField& f, std::span<const FieldSite> sites, double surface_elevation);

// Reads the sources' files once for all the fields of a case (a grid with its locator, a GRDECL's
// arrays, an INIT's, a map, a cell field) and samples them.
class FieldSources {
public:
  FieldSources();
  ~FieldSources();
  FieldSources(const FieldSources&) = delete;
  FieldSources& operator=(const FieldSources&) = delete;

  // The field at the sites. InputError at f.where naming the file for a missing keyword, an
  // array of the wrong size, a cell field of the wrong length or components.
  Sampled sample(const MaterialField& f, std::span<const FieldSite> sites, double surface_elevation);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs
