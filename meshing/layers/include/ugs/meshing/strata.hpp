// The stratigraphy file of ugs-meshgen (TOML, docs/meshing.md) and its evaluation on a plan:
// surfaces top to bottom (constant, GDAL raster sampled bilinearly, horizon grid or TSurf of a
// modelling package, or scattered picks through natural-neighbour interpolation), units between them with their sub-layers, material rules
// (unit + optional polygon -> material, first match wins) and the depth ranges of the plan's faults.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "ugs/meshing/fault_traces.hpp"
#include "ugs/meshing/layered_mesh.hpp"
#include "ugs/meshing/plan.hpp"
#include "ugs/meshing/surface_stack.hpp"

namespace ugs {

struct StrataSurface {
  // Grid: a horizon file of a modelling package (IRAP classic ASCII, CPS-3 ASCII, ZMAP+, GOCAD
  // TSurf; horizon_grids.hpp), told by its content.
  enum class Source { Constant, Raster, Picks, Grid };
  std::string name, where;     // where = "file:line" of its [[surface]] table
  Source source = Source::Constant;
  double constant = 0;
  std::string path;            // raster, picks or grid file, resolved against the strata file's folder
  std::string crs, crs_where;  // a grid's CRS as written ("" = the file's crs)
  int band = 1;
  bool unconformity = false;
};

struct StrataUnit {
  std::string name, where;
  int layers = 1;
  double bias = 1.0;
};

struct MaterialRule {
  std::string name, where;
  std::vector<std::string> units;
  std::string polygon;         // OGR file ("" = no polygon: default for its units)
  std::string filter;          // OGR attribute filter on the polygon file ("" = every feature)
};

struct FaultRange {
  std::string name, where;
  double top = 0, bottom = 0;  // elevations (m), top >= bottom
  // Optional: a dip makes the fault a dipping one (docs/dipping-faults.md); the trace comes from
  // the faults file, else from the plan's line group fault:<name>.
  std::optional<double> dip_deg, dip_dir_deg, trace_z;
  std::vector<FaultTrace::Piece> segments;   // [[fault.segment]]: listric pieces, top to bottom
  std::string ends_against;
  bool has_dip() const { return dip_deg.has_value() || !segments.empty(); }
};

struct Strata {
  std::string file;
  std::string crs;                      // as written; "" = from the first raster, else EPSG:32632
  std::string crs_where;
  double min_thickness = 0.5;           // m
  double order_tolerance = 1.0;         // m
  bool overlap_first_wins = false;      // material_overlap = "first" (default "error")
  std::vector<StrataSurface> surfaces;
  std::vector<StrataUnit> units;
  std::vector<MaterialRule> materials;
  std::string faults_file;              // OGR file with name, top_m, bottom_m per fault ("" = none)
  std::vector<FaultRange> faults;       // [[fault]] tables (override the file)
};

// Reads and checks the file (strict: unknown keys are errors). Throws InputError "file:line: ...".
Strata read_strata(const std::string& path);

struct PreparedModel {
  LayeredMeshInput input;               // ready for build_layered_mesh (input.plan = the plan given)
  StackReport stack;
  std::string crs;                      // label of the model CRS
  std::vector<std::string> notes;       // decisions worth telling the user (-v)
  std::vector<std::string> warnings;
  // Faults built by cutting the layered mesh (cut_faults, fault_cut.hpp): every fault of the faults
  // file or of [[fault]] with a dip below 90 degrees or listric pieces, and vertical ones without a
  // plan line. Checked: trace inside the plan, depth range inside the model.
  std::vector<FaultTrace> cut_faults;
};

// Samples every surface at the plan columns, applies the order rule and pinch-outs, assigns a
// material to each (unit, triangle) by the triangle's centroid, and resolves the depth range of
// each fault:<name> line group of the plan. Bad input (missing or unreadable files, rasters that do
// not cover the plan, no-data, surfaces out of order, rules that overlap partly) throws InputError
// naming the surface or rule, the plan column and its coordinates.
PreparedModel prepare_model(const Strata& strata, const Plan& plan);

}  // namespace ugs
