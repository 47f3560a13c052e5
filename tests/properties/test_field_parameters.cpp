// A constant given as a field is varied by ugs-calibrate and ugs-ensemble through its scale factor
// (analysis/runner/case_params.hpp): the parameter path of the constant names the field's `scale`.
#include <gtest/gtest.h>

#include "input_error.hpp"
#include "case_toml.hpp"
#include <functional>

#include "run_tool.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/runner/case_params.hpp"

using namespace ugs;

TEST(FieldParameters, TheConstantsPathSetsItsScale) {
  test::TempDir d("field-params");
  testcase::CaseToml c;
  c.material({.name = "pool_c", .law = "hypoplastic",
              .more = "c_R = { elevation_table = [[-2000, 2.0], [-1000, 4.0]], scale = 1.0 }\n"
                      "K_m_per_s = [1e-6, { elevation_table = [[-2000, 1e-7], [0, 1e-7]], scale = 3.0 }, 1e-7]\n"});
  c.material({.name = "rock", .more = "porosity = { elevation_table = [[-1, 0.2], [0, 0.2]] }\n"});
  testcase::write_text(d / "case.toml", c.str());
  const runner::CaseTemplate tmpl(d / "case.toml");
  EXPECT_EQ(tmpl.value("material.pool_c.c_R"), 1.0);
  EXPECT_EQ(tmpl.value("material.pool_c.c_R.scale"), 1.0);
  EXPECT_EQ(tmpl.value("material.pool_c.K_m_per_s[1]"), 3.0);
  const CaseFile r = runner::read_rendered_case(tmpl, {{"material.pool_c.c_R", 2.5}, {"material.pool_c.K_m_per_s[1]", 0.5}});
  ASSERT_NE(r.materials[0].field("c_R"), nullptr);
  EXPECT_EQ(r.materials[0].field("c_R")->scale, 2.5);
  EXPECT_EQ(r.materials[0].field("c_R")->rows.size(), 2u);  // the table itself unchanged
  EXPECT_EQ(r.materials[0].field("K_m_per_s[1]")->scale, 0.5);
  EXPECT_EQ((*r.materials[0].K)[0], 1e-6);
  const std::string text = tmpl.render({{"material.pool_c.c_R", 2.5}});
  EXPECT_NE(text.find("c_R = { elevation_table = [[-2000, 2.0], [-1000, 4.0]], scale = 2.5 }"), std::string::npos) << text;
  // Both spellings name one value; a field without `scale` says how to give one.
  const std::string twice = test::input_error_of([&] {
    runner::check_parameters(tmpl, {runner::parse_parameter("material.pool_c.c_R,material.pool_c.c_R.scale=1:3")});
  });
  EXPECT_NE(twice.find("name the same value of the case"), std::string::npos) << twice;
  EXPECT_NE(test::input_error_of([&] { tmpl.value("material.rock.porosity"); }).find("it is a field; write scale = 1.0 in its { ... }"),
            std::string::npos);
  // The bounds are checked like a number's: a scale the field's table cannot take (c_R > 0 holds
  // for any positive scale; a porosity scale of 6 makes 1.2).
  testcase::CaseToml p;
  p.material({.name = "rock", .more = "porosity = { elevation_table = [[-1, 0.2], [0, 0.2]], scale = 1 }\n"});
  testcase::write_text(d / "p.toml", p.str());
  const std::string range = test::input_error_of([&] {
    runner::check_parameters(runner::CaseTemplate(d / "p.toml"), {runner::parse_parameter("material.rock.porosity=0.5:6")});
  });
  EXPECT_NE(range.find("the case is not valid at material.rock.porosity = 6"), std::string::npos) << range;
  EXPECT_NE(range.find("row 1: porosity = 1.2"), std::string::npos) << range;  // 6 x 0.2, rounded up
  EXPECT_NE(range.find("outside (0, 1)"), std::string::npos) << range;
}
