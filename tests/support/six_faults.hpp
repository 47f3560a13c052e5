// The six crossing faults of the benchmark box (8.4 x 8.4 km, 6.8 km deep): two regional faults
// dipping 45 degrees from -500 to -6,600 m and four buried vertical local ones, as written to
// bench/faultinsert's faults.geojson and cut into bench/faulted's mesh.
#pragma once

namespace ugs::testcase {

struct BoxFault {
  const char* name;
  double x0, y0, x1, y1, top, bottom, dip, dip_dir;  // trace ends [m], top and bottom [m], degrees
};

inline constexpr BoxFault kSixFaults[] = {
    {"regional_west", 7000, 0, 7000, 8400, -500, -6600, 45, 270},
    {"regional_south", 0, 7000, 8400, 7000, -500, -6600, 45, 180},
    {"local_1", 3000, 2000, 3000, 6000, -2000, -4000, 90, 90},
    {"local_2", 3000, 1500, 7000, 1500, -1000, -3000, 90, 0},
    {"local_3", 4000, 2000, 7000, 5000, -4000, -6000, 90, 135},
    {"local_4", 1000, 3000, 5000, 7000, -3000, -5000, 90, 315},
};

}  // namespace ugs::testcase
