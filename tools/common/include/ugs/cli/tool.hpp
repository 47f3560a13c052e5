// The shared command-line layer of every ugs tool (docs/cli.md): CLI11 parsing with the common
// options (-o, -v, -q, --version, --help with a worked example), logging and progress on stderr,
// and the single exit path that turns typed errors into one line and an exit code:
//   0 done, 1 the computation failed (ugs::ComputeError), 2 bad usage or input (ugs::InputError).
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace ugs::cli {

struct ToolInfo {
  std::string name;     // e.g. "ugs-meshinfo"
  std::string summary;  // one sentence: what it computes
  std::string example;  // a worked example shown by --help
};

class Tool {
public:
  explicit Tool(ToolInfo info);

  CLI::App& app() { return app_; }
  const ToolInfo& info() const { return info_; }
  // Adds -o/--output with the given default ("-" = stdout) and returns a reference to its value.
  std::string& add_output(const std::string& default_path, const std::string& what);
  std::string& output() { return output_; }

  // Library code names the caller's settings in words ("end date"), never a tool's flags: a line
  // whose place is the setting (`setting: ...`) or one value of it (`setting VALUE: ...`, VALUE
  // without spaces) is printed with the flag in the setting's place (`flag: ...`, `flag VALUE: ...`),
  // and the first other mention of the setting gets " (flag)" after it (unless the line names the flag).
  void name_setting(const std::string& setting, const std::string& flag) { settings_.emplace_back(setting, flag); }
  // `line` with the flags of the settings it names (also for notes and warnings).
  std::string with_flags(std::string line) const;

  // Parses argv and runs `body` inside the one place where errors surface. Returns the exit code.
  int run(int argc, char** argv, const std::function<void()>& body);

  // The command line as typed, for $UgsProvenance and file headers.
  const std::string& command_line() const { return command_line_; }

private:
  ToolInfo info_;
  CLI::App app_;
  std::string output_ = "-";
  std::string command_line_;
  std::vector<std::pair<std::string, std::string>> settings_;  // setting in words -> flag
};

// What the tool is doing, for "out of memory while <activity>" (Tool::run; also when std::bad_alloc
// escapes where it cannot be caught, e.g. inside gmsh, through std::terminate). Restored on exit.
class Activity {
public:
  explicit Activity(const std::string& what);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

private:
  std::string previous_;
};

// Verbosity: -q gives -1, default 0, each -v adds one.
int verbosity();
void set_verbosity(int v);
const std::string& tool_name();

// Messages on stderr, prefixed with the tool name; `info` shows at verbosity >= 0, `detail` at >= 1.
template <class... A>
void info(fmt::format_string<A...> f, A&&... a);
template <class... A>
void detail(fmt::format_string<A...> f, A&&... a);
template <class... A>
void warning(fmt::format_string<A...> f, A&&... a);
void print_line(int min_verbosity, const std::string& prefix, const std::string& text);

template <class... A>
void info(fmt::format_string<A...> f, A&&... a) { print_line(0, "", fmt::format(f, std::forward<A>(a)...)); }
template <class... A>
void detail(fmt::format_string<A...> f, A&&... a) { print_line(1, "", fmt::format(f, std::forward<A>(a)...)); }
template <class... A>
void warning(fmt::format_string<A...> f, A&&... a) { print_line(-1, "warning: ", fmt::format(f, std::forward<A>(a)...)); }

// Progress of long work on stderr: a bar on a terminal, a line every few seconds otherwise.
class Progress {
public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  void update(std::size_t done);
  void finish();

private:
  std::string label_;
  std::size_t total_;
  bool tty_, finished_ = false;
  double start_, last_print_;
};

}  // namespace ugs::cli
