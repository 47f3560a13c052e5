// The seismicity forecast of a stress history: per node pair and date R / r and the expected events
// per unit area from a start date, per fault and date the area-weighted R / r, its largest value,
// the rate (events >= M_c per year) and the expected events from the start, and per window the
// expected events >= M_c (exact integrals of R, rate_state.hpp). Magnitudes above M_c through
// Gutenberg-Richter: N(M) = N(M_c) 10^(-b (M - M_c)); P(at least one) = 1 - exp(-N) (Poisson).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/seismicity/histories.hpp"

namespace ugs::seismicity {

// The parameters of one fault, SI: Pa, Pa/s, events per s per m2.
struct Parameters {
  double A_sigma = 0, stressing_rate = 0, background_rate = 0, M_c = 0, b_value = 1;
};

// The fault's parameters: [seismicity.fault.<name>] where it gives a value, else [seismicity].
// InputError (at the case) when a required value is missing.
Parameters parameters_for(const SeismicitySpec& spec, const std::string& fault, const std::string& case_path);
// Each fault named by the case — every [seismicity.fault.<name>], and with `case_faults` every
// [[fault]] — must be in the results: InputError at the case's line otherwise, listing the results'.
void check_case_faults(const CaseFile& c, const StressHistory& h, bool case_faults);

struct Window {
  std::int64_t start = 0, end = 0;  // seconds since 1970
};
// "START/END" (ISO dates, START before END); InputError at `where` otherwise.
Window parse_window(const std::string& text, const std::string& where);

struct PairForecast {
  std::vector<double> rate_ratio;       // R / r per date
  std::vector<double> events_per_m2;    // expected events >= M_c per m2 from the start date (0 before it)
};

struct FaultForecast {
  std::string name;
  Parameters params;
  double area = 0;                      // m2, sum of the pairs' shares
  // Per date:
  std::vector<double> cfs_mean;         // area-weighted Coulomb stress change, Pa
  std::vector<double> rate_ratio;       // area-weighted R / r
  std::vector<double> rate_ratio_max;   // largest R / r over the pairs with area (not interpolated ones, when any)
  std::vector<double> rate;             // events >= M_c per second: r sum_q A_q (R / r)_q
  std::vector<double> events;           // expected events >= M_c from the start date
  std::vector<double> window_events;    // per window: expected events >= M_c
  std::vector<PairForecast> pairs;
};

struct Forecast {
  std::vector<std::int64_t> dates;
  std::int64_t start = 0;
  std::vector<Window> windows;
  std::vector<FaultForecast> faults;
};

// InputError for a start date or a window outside the history, a fault without area, or a first
// step of more than ~700 A sigma (R / r would not fit a double).
Forecast forecast(const StressHistory& h, const std::vector<Parameters>& params, std::int64_t start,
                  const std::vector<Window>& windows);

// Expected events of magnitude >= m from those >= M_c (Gutenberg-Richter, any m).
double events_above(double events_mc, const Parameters& p, double m);
// P(at least one event) of a Poisson count with mean n: 1 - exp(-n), exact also for small n.
double probability_at_least_one(double n);

}  // namespace ugs::seismicity
