// GRDECL: the keyword text of ECLIPSE decks that geomodelling packages export (Petrel, RMS,
// ResInsight) and simulators read — a keyword on its line, its values up to '/', runs of equal
// values as N*value, '--' comments, INCLUDE of other files (docs/case-file.md, "Properties that vary
// in space"). The corner-point grid it describes: corner_point_grid.hpp.
#pragma once
#include <set>
#include <string>
#include <vector>

namespace ugs {

struct GrdeclKeyword {
  std::string name;                 // upper case
  std::string where;                // "file:line" of the keyword
  std::vector<double> values;       // numbers, N*v expanded
  std::vector<std::string> words;   // the items that are not numbers (quoted names, F/T flags), in order
};

struct GrdeclFile {
  std::string path;
  std::vector<GrdeclKeyword> keywords;  // in file order (INCLUDEd files in place)
  const GrdeclKeyword* find(const std::string& name) const;  // the last one of that name, or nullptr
  std::string names() const;            // "SPECGRID, COORD, ..." for messages
};

// Reads every keyword (only the values of those in `values_of` when it is not empty: the others
// are skipped, not stored). InputError "file:line: ..." for a missing file, a keyword without its
// closing '/', a repeat count that is not a positive integer, a number out of range.
GrdeclFile read_grdecl(const std::string& path, const std::set<std::string>& values_of = {});

}  // namespace ugs
