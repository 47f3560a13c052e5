// The stages of the fault cut that are more than one call on the Cutter (cutter.hpp), in the order
// cut_faults (fault_cut.cpp) runs them, each defined in the file named beside it.
#pragma once

#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/fault_cut.hpp"
#include "ugs/meshing/fault_traces.hpp"

namespace ugs::fault_cut {

class Cutter;

// cut_panels.cpp: every trace's panels (fault_cut_panels), in the traces' order; InputError when the
// mesh already has the group fault:<name>.
std::vector<std::vector<CutPanel>> panels_of(const Mesh& mesh, const std::vector<FaultTrace>& traces);
// cut_surface_panels.cpp: the panels of a fault given as a surface (trace.surface), one per triangle.
std::vector<CutPanel> surface_panels(const FaultTrace& trace);

// cut_fault_faces.cpp: per fault, the faces lying in its panels (each once; those on the model's
// boundary counted, not kept) become its group; a report per fault is started. Returns the names.
// InputError when a fault's surface does not cross the mesh.
std::vector<std::string> add_fault_groups(Cutter& cut, const std::vector<FaultTrace>& traces,
                                          const std::vector<std::vector<CutPanel>>& panels, std::vector<FaultCutReport>& reports);

// cut_cleanup.cpp: collapse and smoothing in the band the cut made (collapsed, smoothed).
void improve_band(Cutter& cut, const FaultCutOptions& options, FaultCutSummary& sum);

// cut_report.cpp: the band's quality (band_*), then each fault's faces against its panels.
void measure_band(const Cutter& cut, const FaultCutOptions& options, FaultCutSummary& sum);
void measure_faults(const Cutter& cut, const std::vector<FaultTrace>& traces, const std::vector<std::vector<CutPanel>>& panels,
                    FaultCutSummary& sum);

}  // namespace ugs::fault_cut
