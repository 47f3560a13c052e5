// Case-file parameters as ugs-calibrate (--param PATH[,PATH...]=LOWER:UPPER[:log]) and ugs-ensemble
// name them (analysis/runner/src/case_params.cpp): the input is a TOML case, a line "%%", then one
// parameter per line (up to 4 accepted ones: each costs a dozen parses of the case). The case is
// read as runner::CaseTemplate, each parameter parsed (parse_parameter), its paths looked up
// (value), the case rendered with every path of a parameter at its lower and at its upper bound,
// then check_parameters (what both tools do before running) and referenced_files. A rendered copy
// must read back: the same paths hold the values set.
#include <cstdio>
#include <sstream>

#include "fuzz_support.hpp"
#include "ugs/runner/case_params.hpp"

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_case_params: %s\n", what.c_str());
  std::abort();
}

// Renders the case with `values` and reads the copy back.
void render_and_reread(const ugs::runner::CaseTemplate& tmpl, const std::vector<std::pair<std::string, double>>& values) {
  const std::string text = tmpl.render(values);
  const std::string copy = ugs::fuzz::write_temp("copy.toml", reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  std::string step = "reading the rendered copy";
  try {
    const ugs::runner::CaseTemplate back(copy);
    for (const auto& [p, v] : values) {
      step = "the value of " + p + " in the rendered copy";
      const double got = back.value(p);
      if (got != v) finding(p + " set to " + ugs::runner::toml_float(v) + " reads back as " + ugs::runner::toml_float(got));
    }
  } catch (const ugs::InputError& e) {
    finding(step + ": " + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input = ugs::fuzz::text(data, size);
  const auto sep = input.find("\n%%\n");
  const std::string case_text = input.substr(0, sep == std::string::npos ? input.size() : sep + 1);
  const std::string params = sep == std::string::npos ? "" : input.substr(sep + 4);
  const std::string path = ugs::fuzz::write_temp("case.toml", reinterpret_cast<const std::uint8_t*>(case_text.data()), case_text.size());
  ugs::fuzz::outcome([&] {
    const ugs::runner::CaseTemplate tmpl(path);
    (void)tmpl.referenced_files();
    std::vector<ugs::runner::ParameterSpec> specs;
    std::istringstream lines(params);
    for (std::string line; std::getline(lines, line) && specs.size() < 4;) {
      if (line.empty()) continue;
      ugs::fuzz::outcome([&] {
        const ugs::runner::ParameterSpec p = ugs::runner::parse_parameter(line);
        for (const auto& q : p.paths) (void)tmpl.value(q);
        for (double v : {p.lower, p.upper}) {
          std::vector<std::pair<std::string, double>> values;
          for (const auto& q : p.paths) values.emplace_back(q, v);
          render_and_reread(tmpl, values);
        }
        specs.push_back(p);
      });
    }
    if (!specs.empty()) (void)ugs::runner::check_parameters(tmpl, specs);
  });
  return 0;
}
