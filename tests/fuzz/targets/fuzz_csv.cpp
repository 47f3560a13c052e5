// CSV tables (formats/src/csv.cpp): the reader, then every typed access tools make on its cells
// (numbers, integers, dates by column).
#include <algorithm>

#include "fuzz_support.hpp"
#include "ugs/formats/csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ugs::fuzz::outcome([&] {
    auto in = ugs::InputStream::from_string(ugs::fuzz::text(data, size), "fuzz.csv");
    const ugs::CsvTable t = ugs::CsvTable::read(*in);
    for (const std::string& c : t.columns()) {
      ugs::fuzz::outcome([&] { (void)t.numbers(c); });
      ugs::fuzz::outcome([&] { (void)t.dates(c); });
      ugs::fuzz::outcome([&] { (void)t.column(c); });
    }
    const std::size_t rows = std::min<std::size_t>(t.rows(), 16);
    for (std::size_t r = 0; r < rows; ++r) {
      (void)t.where(r);
      for (std::size_t c = 0; c < t.columns().size(); ++c) {
        (void)t.text(r, c);
        ugs::fuzz::outcome([&] { (void)t.integer(r, c); });
        ugs::fuzz::outcome([&] {
          const auto d = t.date(r, c);
          (void)ugs::format_iso_date(d);
        });
      }
    }
  });
  // The date parser alone, on the whole input as one cell.
  if (size < 64) {
    if (auto d = ugs::parse_iso_date(ugs::fuzz::text(data, size))) (void)ugs::format_iso_date(*d);
  }
  return 0;
}
