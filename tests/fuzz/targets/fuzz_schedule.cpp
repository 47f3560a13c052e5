// Pool pressure schedules (solver/flow/src/schedule.cpp), as ugs-flow and ugs-solve read them:
// a p_norm schedule with a reference pressure and a p_MPa one, then the run window and the time
// grid built from them, and the interpolation at a few dates.
#include <vector>

#include "fuzz_support.hpp"
#include "ugs/flow/schedule.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("schedule.csv", data, size);
  for (const char* column : {"p_norm", "p_MPa"}) {
    ugs::fuzz::outcome([&] {
      ugs::PoolSpec pool;
      pool.name = "Pool F";
      pool.schedule = path;
      pool.column = column;
      if (pool.column == "p_norm") pool.reference_pressure_Pa = 15e6;
      const ugs::flow::PoolSchedule s = ugs::flow::read_pool_schedule(pool);
      ugs::CaseFile c;
      c.path = "case.toml";
      const std::vector<ugs::flow::PoolSchedule> all{s};
      const ugs::flow::RunWindow w = ugs::flow::run_window(c, all);
      const ugs::flow::TimeGrid g = ugs::flow::make_time_grid(all, w);
      for (std::int64_t t : {w.start, (w.start + w.end) / 2, w.end}) (void)s.at(t);
      (void)g;
    });
  }
  return 0;
}
