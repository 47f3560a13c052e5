// ugs-report internals: what the figure builders share (inputs, the work folder, the figure list
// handed to plots.py as manifest.json) and the headline numbers of the summary page.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/insar/surface.hpp"

namespace ugs::report {

struct Phase {
  std::string name;            // "storage"
  std::int64_t start = 0, end = 0;
  std::string label() const;   // "storage 2015-05-01 to 2015-11-01"
};

struct Options {
  std::string results, top, mesh, case_file, crs;
  std::string measured, measured_east, samples;
  std::string trace, trace_where, sections, sections_where, faults;
  std::vector<std::string> phases;       // NAME=START/END
  std::string stress_pool;               // pool whose layer the stress pictures look at
  std::string stress_field;              // cell field (default: stress_change, dstress or stress)
  double reference_pressure_MPa = 0;     // normalisation of stress changes (default: the pool's)
  double exaggeration = 10;
  double edge_distance = 500;  // m: a critical fault patch this close to the reservoir trace is at its edge (safety.cpp)
  std::string section_zrange;            // ZMIN/ZMAX
  std::string fault_dates;               // MIN_DATE,MAX_DATE
  std::string fault_field = "chi";
  std::string fault_table;               // ugs-solve's faults CSV (default: <faults stem>.csv beside --faults)
  std::string calibration;               // ugs-calibrate output folder
  std::string ensemble;                  // ugs-ensemble output folder
  std::string seismicity;                // ugs-seismicity's per fault and date table (its _windows and _pairs beside it)
  std::string seismicity_window;         // START/END of the event density map (default: the first window)
  std::string scenario;                  // ugs-solve's safe-scale table (<output>_scenario.csv)
  std::string caprock;                   // ugs-solve's caprock table (<output>_caprock.csv)
  bool thesis = false;                   // compare with the thesis: its phases by default, its values beside ours
  std::vector<std::string> compare;      // LABEL=FILE: other runs on the same mesh
  std::string compare_since;             // changes from this date (default: the first shared date)
  std::string discussion;                // Markdown paragraphs comparing the run with the thesis
  double raster_cell = 0;
  std::string map_extent;                // XMIN/XMAX/YMIN/YMAX
  std::string python;
  bool keep_work = false;
  int width = 1600, height = 1000, dpi = 160;
};

// One figure for plots.py: its kind, PNG name and the JSON members describing its data.
struct Figure {
  std::string kind, png, title, json;   // json: extra members, "key": value, ... (no braces)
  std::string caption;
};

// A number of the summary page next to the thesis' value.
struct Headline {
  std::string group, quantity, value, thesis;
};

// A number an acceptance threshold of the case's [report] is checked against, and where it was found.
struct Measure {
  double value = 0;
  std::string where;
};

struct Context {
  Options opt;
  std::string work;                      // work folder (absolute)
  std::string out;                       // output folder being written (absolute)
  std::optional<CaseFile> cs;
  std::optional<Mesh> mesh;
  std::string crs_wkt;
  std::vector<Phase> phases;
  std::unique_ptr<FieldSeriesReader> results;
  std::vector<std::int64_t> result_times;
  std::string surface_results;            // displacement on the top: ugs-solve's top file, else the results
  std::optional<insar::TopSurface> top;  // its top surface (the mesh's bnd:top, or the file's own cells)
  std::vector<Figure> figures;
  std::vector<Headline> headlines;
  // uplift_max_mm, settlement_max_mm, chi_max, tensile_margin_min_MPa, shear_margin_min_MPa (acceptance.cpp)
  std::map<std::string, Measure> measures;
  std::vector<std::string> notes;        // what was skipped and why
  std::optional<insar::PsData> measured_up, measured_east;
  std::vector<std::vector<std::array<double, 2>>> trace_lines;  // rings of the reservoir trace
  std::vector<std::string> written;      // GeoTIFFs and other data files in the output
  std::string command_line;

  std::string work_file(const std::string& name) const { return work + "/" + name; }
  void add(Figure f) { figures.push_back(std::move(f)); }
};

// JSON text of a string.
std::string jstr(const std::string& s);
// Relative path of a work file as plots.py sees it (work/<name>).
std::string jwork(const std::string& name);
std::string slug(const std::string& s);
// File-name stems for names that share a folder (faults): slug() of each, made unique. Names whose
// slugs collide (F1 and f1, a-b and a_b) keep the plain slug for the first in byte order; the
// others get _2, _3, ... (skipping any stem another name has). Depends only on the set of names:
// the same faults give the same file names in any order.
std::vector<std::string> unique_slugs(const std::vector<std::string>& names);
std::string mm(double v);  // "3.21"

// The pool pressures of the case's schedules, long format (pool,date,value), as work/pressure.csv
// (written once); false without a case or pools. `label`: the axis label.
bool write_pressures(Context& c, std::string& label);

// The lines of --sections (none without it), in file order: name (else "section <fid>"), the
// polyline in the model CRS and the labels of its ends.
struct SectionLine {
  std::string name, from, to;
  std::vector<std::array<double, 2>> polyline;
};
std::vector<SectionLine> section_lines(const Context& c);

// The nodes of each pool's materials (tetrahedra of mat:<name>); empty without a mesh or a case.
using PoolNodes = std::vector<std::pair<std::string, std::vector<Point3>>>;
PoolNodes pool_nodes(const Context& c);
// The pools' outlines (convex hull of their nodes) on a fault's plane, along strike s = x sx + y sy
// - s0 and elevation, as work/<name> (pool,s,z; written once): its jwork, or "null" without pools.
std::string write_pool_outlines(const Context& c, const PoolNodes& pools, const std::string& name, double sx, double sy, double s0);

// The fault's strike (sx, sy) and offset s0 from its pairs' along_strike = x sx + y sy - s0 (least
// squares; along the pairs' line for a vertical fault): for the pools' outlines on its plane.
std::array<double, 3> strike_of(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& s);

// Figure builders (each adds figures, headlines and notes).
void build_maps(Context& c);
void build_series(Context& c);
void build_stress(Context& c);
void build_faults(Context& c);
void build_calibration(Context& c);
void build_ensemble(Context& c);
void build_seismicity(Context& c);
void build_safety(Context& c);
void build_seal_pictures(Context& c);
// Pass / fail of the case's [report] thresholds against the measures (last: after every builder).
void build_acceptance(Context& c);
// The pool the stress pictures look at: --stress-pool, the case's [report] stress_pool, Pool C, the last pool.
std::string wanted_stress_pool(const Context& c);
void build_comparison(Context& c);
// Writes summary.md and summary.html in the output folder.
void write_summary(const Context& c);

// Field values of a step, or interpolated linearly between the steps around `t` (InputError if `t`
// lies outside the results).
std::vector<double> cell_field_at(const FieldSeriesReader& r, const std::vector<std::int64_t>& times, const std::string& name,
                                  std::int64_t t, int& components);

}  // namespace ugs::report
