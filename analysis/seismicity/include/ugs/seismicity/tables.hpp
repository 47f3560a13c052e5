// The forecast's files (docs/seismicity.md "Outputs"): CSV tables in MPa, events per year and km2,
// ISO dates, numbers as the shortest text that reads back to the same double; the node fields on the
// fault surfaces as HDF5 + XDMF for ParaView. Each file appears only on its writer's commit().
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/seismicity/forecast.hpp"

namespace ugs::seismicity {

// Per fault and date: date,fault,cfs_change_mean_MPa,R_over_r,R_over_r_max,rate_per_yr,events_from_start
std::unique_ptr<CsvWriter> fault_table(const std::string& path, const Forecast& fc, const std::vector<std::string>& comments);
// Per window, fault (then "all", the sum over the faults) and magnitude (M_c of the fault, then
// `magnitudes`; "all": every fault's M_c and `magnitudes`, each fault through its own b):
// start,end,fault,magnitude,expected_events,p_at_least_one
std::unique_ptr<CsvWriter> window_table(const std::string& path, const Forecast& fc, const std::vector<double>& magnitudes,
                                        const std::vector<std::string>& comments);
// Per date, fault and node pair: date,fault,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,
// interpolated,cfs_change_MPa,R_over_r,rate_per_yr_km2,events_per_km2_from_start
std::unique_ptr<CsvWriter> pair_table(const std::string& path, const StressHistory& h, const Forecast& fc,
                                      const std::vector<std::string>& comments);
// Node fields R_over_r, rate_per_yr_km2, events_per_km2 (from the start date) at every date on the
// surface of a faults HDF5 input (h.surface); std::logic_error without one.
std::unique_ptr<FieldSeriesWriter> pair_fields(const std::string& h5_path, const StressHistory& h, const Forecast& fc);

}  // namespace ugs::seismicity
