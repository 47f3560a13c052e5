// Reads a CSV table from stdin and prints its row count and the sum of column p_MPa, so a test
// can feed it through a real pipe.
#include <cstdio>
#include <exception>

#include "ugs/formats/csv.hpp"

int main() {
  try {
    const ugs::CsvTable t = ugs::CsvTable::read("-");
    double sum = 0;
    for (double p : t.numbers("p_MPa")) sum += p;
    std::printf("%zu rows, p_MPa sum %g\n", t.rows(), sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "csv_pipe_reader: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
