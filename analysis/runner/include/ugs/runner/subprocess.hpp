// Running an external command (the solver of a calibration evaluation, the plotting script of a
// report): through /bin/sh -c or directly with an argument vector, in a working folder, with
// stdout and stderr appended to a log file. Safe to call from several threads at once.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace ugs::runner {

struct CommandResult {
  int exit_code = -1;      // 128 + signal when killed by a signal
  double seconds = 0;
};

// `cwd` "" = current folder; `log` "" = inherit the caller's stdout/stderr. `env` entries are
// added to (or replace) the environment. ComputeError if the process cannot be started.
CommandResult run_command(const std::vector<std::string>& argv, const std::string& cwd, const std::string& log,
                          const std::map<std::string, std::string>& env = {});
inline CommandResult run_shell(const std::string& command, const std::string& cwd, const std::string& log,
                               const std::map<std::string, std::string>& env = {}) {
  return run_command({"/bin/sh", "-c", command}, cwd, log, env);
}

// Quotes `s` for /bin/sh ('...' with embedded quotes escaped) unless it is plainly safe.
std::string shell_quote(const std::string& s);

// The last non-empty line of a (log) file, at most `max_chars` long; "" if none.
std::string last_line(const std::string& path, std::size_t max_chars = 300);

}  // namespace ugs::runner
