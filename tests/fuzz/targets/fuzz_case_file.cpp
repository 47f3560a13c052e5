// The case file (TOML; formats/src/case_file.cpp over formats/src/toml_reader.cpp), as every tool
// with --case reads it.
#include "fuzz_support.hpp"
#include "ugs/formats/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("case.toml", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::CaseFile c = ugs::read_case_file(path);
    for (const auto& m : c.materials) (void)c.material(m.name);
  });
  return 0;
}
