// Graded 2D plan meshes with the gmsh SDK (what ugs-mesh2d builds): a domain, polygon regions (with
// an optional target size inside), and constraint lines that must become mesh edges (faults,
// sections, traces). The mesh size is the target size inside a refined region and grows linearly
// with the distance from it (`grading` metres of size per metre of distance) up to `hmax`.
//
// Output groups: region:<name> (triangles; the domain's name covers every triangle, regions may
// overlap), <kind>:<name> (line elements of constraint lines, e.g. fault:<name>, oriented along the
// input line) and trace:<name> for the outline of polygon traces.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/geodata.hpp"

namespace ugs {

struct PlanRegion {
  std::string name;
  std::vector<geo::Polygon> polygons;   // inside the domain
  double size = 0;                      // target size inside (m); 0 = constraint only
  std::string outline_group;            // if set, the outline also becomes this line group (e.g. "trace:Pool A")
};

struct PlanLine {
  std::string group;                    // physical name, e.g. "fault:local_1"
  std::vector<std::vector<XY>> lines;   // polylines inside the domain
  double size = 0;                      // target size along the line (m); 0 = constraint only
};

// The widest plan meshed (m): a domain wider than this is a coordinate out of place (4294967295
// typed for 690000 made a sliver 4.3 million km long: 8e6 triangles under the element limit and
// minutes of meshing), refused before meshing.
constexpr double kMaxPlanExtentM = 1.0e6;

struct PlanSpec {
  std::string domain_name = "domain";
  std::vector<geo::Polygon> domain;
  double hmax = 2000;                   // size far from every refinement (m)
  double grading = 0.5;                 // size growth per unit distance
  std::vector<PlanRegion> regions;
  std::vector<PlanLine> lines;
  int algorithm = 6;                    // gmsh Mesh.Algorithm (6 Frontal-Delaunay, 5 Delaunay, 8 ...)
  bool gmsh_messages = false;           // let gmsh print its log on stderr
  double max_triangles = 20e6;          // refuse sizes whose estimated triangle count is above this
};

// How many triangles the size field asks for, before meshing: kTrianglesPerSquare x the integral of
// 1 / h^2 over the domain, with h = hmax in the far field, the target size s inside each refinement
// polygon and s + grading * d in the band around it (and around refined lines), whose integral is
// perimeter / grading * (1 / s - 1 / hmax). Overlaps are counted twice (an over-estimate). The
// po-plain plan (13,532 nodes): 26,990 triangles made, estimate within a factor of 2 (tests).
constexpr double kTrianglesPerSquare = 2.3094010767585;  // 4 / sqrt(3): equilateral triangles of edge h per h^2
struct PlanEstimate {
  double triangles = 0;
  double smallest_size = 0;             // m
  std::string smallest_where;           // "region 'x'", "line fault:y" or "the far field (hmax)"
};
PlanEstimate estimate_plan_triangles(const PlanSpec& spec);

struct PlanMeshStats {
  std::size_t nodes = 0, triangles = 0, line_elements = 0;
  double min_size = 0;                  // smallest target size used
};

// Builds the plan; ComputeError if gmsh fails (with gmsh's message).
Mesh make_plan_mesh(const PlanSpec& spec, PlanMeshStats* stats = nullptr);

// ---- inputs from vector files (ugs-mesh2d's options) --------------------------------------------
struct PlanInputs {
  std::string domain_file;                       // polygon(s); or
  bool use_box = false;
  std::array<double, 4> box{};                   // xmin, xmax, ymin, ymax
  std::vector<std::string> refine_files;         // polygons with a size field
  std::vector<std::string> trace_files;          // polygons (regions + outline) or lines
  std::vector<std::string> fault_files, section_files;  // lines
  double hmax = 0;                               // 0 = from the domain's size field
  double grading = 0.5;
  double refine_size = 0;                        // 0 = every refinement feature needs the size field
  std::string crs;                               // "" = from the first input with a CRS, else EPSG:32632
  std::string name_field = "name", size_field = "size_m";
};

struct LoadedPlan {
  PlanSpec spec;
  std::string crs;                               // label of the model CRS
  std::vector<std::string> notes, warnings;
};

// Reads every file through OGR, reprojects to the model CRS, clips to the domain (GEOS) and names
// features by `name_field` (else <layer>_<fid>). Features with the same kind and name form one group.
LoadedPlan load_plan_inputs(const PlanInputs& in);

}  // namespace ugs
