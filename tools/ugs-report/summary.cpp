// The one-page summary: headline numbers next to the thesis' (TOOLCHAIN.md, "The reference case"),
// every figure with its caption, the GeoTIFFs, and what was skipped. Markdown and HTML.
#include <fmt/format.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"

namespace ugs::report {

namespace {

std::string html(const std::string& s) {
  std::string r;
  for (char ch : s) {
    switch (ch) {
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '&': r += "&amp;"; break;
      case '"': r += "&quot;"; break;
      default: r += ch;
    }
  }
  return r;
}

std::string md_cell(const std::string& s) {
  std::string r;
  for (char ch : s) {
    if (ch == '|') r += '\\';
    r += ch;
  }
  return r;
}

std::string read_discussion(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot read the discussion file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The first number of a headline's text ("3.21 mm at (x, y)" -> 3.21), for scripts and tests.
std::optional<double> leading_number(const std::string& s) {
  static const std::regex number(R"([-+]?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?)");
  std::smatch m;
  if (!std::regex_search(s, m, number)) return std::nullopt;
  return std::stod(m.str());
}

// paragraphs -> <p>, '- ' lines -> <li>; enough for the notes a case ships with.
std::string discussion_html(const std::string& md) {
  std::string out, para;
  bool in_list = false;
  auto flush = [&] {
    if (!para.empty()) out += "<p>" + html(para) + "</p>\n";
    para.clear();
  };
  std::istringstream in(md);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("- ", 0) == 0) {
      flush();
      if (!in_list) out += "<ul>\n";
      in_list = true;
      out += "<li>" + html(line.substr(2)) + "</li>\n";
    } else if (line.find_first_not_of(" \t\r") == std::string::npos) {
      flush();
      if (in_list) out += "</ul>\n";
      in_list = false;
    } else if (in_list && line.rfind("  ", 0) == 0) {
      out.insert(out.size() - 6, " " + html(line.substr(line.find_first_not_of(' '))));
    } else {
      if (in_list) out += "</ul>\n";
      in_list = false;
      para += (para.empty() ? "" : " ") + line;
    }
  }
  flush();
  if (in_list) out += "</ul>\n";
  return out;
}

}  // namespace

void write_summary(const Context& c) {
  const std::string discussion = c.opt.discussion.empty() ? std::string() : read_discussion(c.opt.discussion);
  const std::string title = fmt::format("ugs report: {}", c.cs ? c.cs->path : c.opt.results);
  std::vector<std::pair<std::string, std::string>> inputs{{"results", c.opt.results}, {"top-surface series", c.surface_results}};
  if (!c.opt.mesh.empty()) inputs.emplace_back("mesh", c.opt.mesh);
  if (!c.opt.case_file.empty()) inputs.emplace_back("case", c.opt.case_file);
  if (!c.opt.measured.empty()) inputs.emplace_back("measured (vertical)", c.opt.measured);
  if (!c.opt.measured_east.empty()) inputs.emplace_back("measured (east)", c.opt.measured_east);
  if (!c.opt.samples.empty()) inputs.emplace_back("samples", c.opt.samples);
  if (!c.opt.faults.empty()) inputs.emplace_back("fault results", c.opt.faults);
  if (!c.opt.calibration.empty()) inputs.emplace_back("calibration", c.opt.calibration);
  std::string phases;
  for (const auto& p : c.phases) phases += (phases.empty() ? "" : "; ") + p.label();

  // Markdown.
  std::string md = "# " + title + "\n\n";
  for (const auto& [k, v] : inputs) md += fmt::format("- {}: `{}`\n", k, v);
  // The thesis' column only when the comparison is asked for (--thesis): a field's report has its own numbers.
  const bool thesis = c.opt.thesis;
  md += "- phases: " + phases + "\n\n## Headline numbers\n\n";
  md += thesis ? "| | quantity | this run | thesis |\n|---|---|---|---|\n" : "| | quantity | this run |\n|---|---|---|\n";
  for (const auto& h : c.headlines)
    md += thesis ? fmt::format("| {} | {} | {} | {} |\n", md_cell(h.group), md_cell(h.quantity), md_cell(h.value), md_cell(h.thesis))
                 : fmt::format("| {} | {} | {} |\n", md_cell(h.group), md_cell(h.quantity), md_cell(h.value));
  if (!discussion.empty()) md += "\n## Comparison with the thesis\n\n" + discussion + (discussion.back() == '\n' ? "" : "\n");
  md += "\n## Figures\n\n";
  for (const auto& f : c.figures) md += fmt::format("### {}\n\n![{}]({})\n\n{}\n\n", f.title, f.title, f.png, f.caption);
  if (!c.written.empty()) {
    md += "## GeoTIFF maps\n\n";
    for (const auto& w : c.written) md += fmt::format("- [{}]({})\n", w, w);
    md += "\n";
  }
  if (!c.notes.empty()) {
    md += "## Notes\n\n";
    for (const auto& n : c.notes) md += "- " + n + "\n";
    md += "\n";
  }
  md += fmt::format("Made by `{}`\n", c.command_line);
  OutputFile fm(c.out + "/summary.md");
  fm.write(md);
  fm.commit();

  // HTML, self-contained apart from the PNGs beside it.
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + html(title) +
                  "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
                  "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:4px 8px;text-align:left}"
                  "img{max-width:100%}figure{margin:1.5em 0}figcaption{font-size:90%;color:#444}</style></head><body>\n";
  h += "<h1>" + html(title) + "</h1>\n<ul>\n";
  for (const auto& [k, v] : inputs) h += fmt::format("<li>{}: <code>{}</code></li>\n", html(k), html(v));
  h += "<li>phases: " + html(phases) + "</li>\n</ul>\n<h2>Headline numbers</h2>\n<table>\n"
       "<tr><th></th><th>quantity</th><th>this run</th>" + std::string(thesis ? "<th>thesis</th>" : "") + "</tr>\n";
  for (const auto& x : c.headlines)
    h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td>{}</tr>\n", html(x.group), html(x.quantity), html(x.value),
                     thesis ? "<td>" + html(x.thesis) + "</td>" : "");
  h += "</table>\n";
  if (!discussion.empty()) h += "<h2>Comparison with the thesis</h2>\n" + discussion_html(discussion);
  h += "<h2>Figures</h2>\n";
  for (const auto& f : c.figures)
    h += fmt::format("<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n", html(f.png), html(f.title),
                     html(f.caption));
  if (!c.written.empty()) {
    h += "<h2>GeoTIFF maps</h2>\n<ul>\n";
    for (const auto& w : c.written) h += fmt::format("<li><a href=\"{}\">{}</a></li>\n", html(w), html(w));
    h += "</ul>\n";
  }
  if (!c.notes.empty()) {
    h += "<h2>Notes</h2>\n<ul>\n";
    for (const auto& n : c.notes) h += "<li>" + html(n) + "</li>\n";
    h += "</ul>\n";
  }
  h += "<p><small>Made by <code>" + html(c.command_line) + "</code></small></p>\n</body></html>\n";
  OutputFile fh(c.out + "/summary.html");
  fh.write(h);
  fh.commit();

  // The same numbers for scripts: value_number is the first number of the value's text (mm, chi, m...).
  CsvWriter w(c.out + "/headlines.csv", {"group", "quantity", "value", "value_number", "thesis"});
  for (const auto& x : c.headlines) {
    w.text(x.group).text(x.quantity).text(x.value);
    if (const auto v = leading_number(x.value)) w.number(*v);
    else w.text("");
    w.text(thesis ? x.thesis : "").end_row();
  }
  w.commit();
}

}  // namespace ugs::report
