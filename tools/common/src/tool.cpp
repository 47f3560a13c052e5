#include "ugs/cli/tool.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>

#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/version.hpp"

namespace ugs::cli {
namespace {
int g_verbosity = 0;
std::string g_tool = "ugs";

double now_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string quote_arg(const std::string& a) {
  if (!a.empty() && a.find_first_of(" \t\"'$\\") == std::string::npos) return a;
  std::string q = "'";
  for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Help that ends with the worked example, as GMT's usage() does.
class HelpFormatter : public CLI::Formatter {
public:
  explicit HelpFormatter(std::string example) : example_(std::move(example)) {}
  std::string make_footer(const CLI::App* app) const override {
    std::string f = CLI::Formatter::make_footer(app);
    return f + "\nExample:\n  " + example_ + "\n\nExit codes: 0 done, 1 computation failed, 2 bad usage or input.\n";
  }

private:
  std::string example_;
};

// The activity in a fixed buffer: the terminate handler prints it without allocating.
char g_activity[256] = "running";

void set_activity(const std::string& what) {
  const std::size_t n = std::min(what.size(), sizeof g_activity - 1);
  std::memcpy(g_activity, what.data(), n);
  g_activity[n] = '\0';
}

// std::bad_alloc (or any exception) escaping where it cannot be caught (a noexcept function, a
// library's thread) ended in SIGABRT: one line and exit 1 instead, temporary outputs removed.
[[noreturn]] void on_terminate() {
  bool oom = false;
  const char* what = "std::terminate called";
  if (std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      oom = true;
    } catch (const std::exception& x) {
      what = x.what();
    } catch (...) {
      what = "unknown exception";
    }
  }
  remove_uncommitted_outputs();
  if (oom) std::fprintf(stderr, "%s: error: out of memory while %s\n", g_tool.c_str(), g_activity);
  else std::fprintf(stderr, "%s: error: internal error: %s\n", g_tool.c_str(), what);
  std::fflush(stderr);
  std::_Exit(1);
}
// After the one error line nothing else may reach stderr. The libraries' shutdown still follows
// (MPI_Finalize ends libhdf5 through its MPI_COMM_SELF callback, whatever H5dont_atexit says), and
// after a damaged file libhdf5 1.10 cannot free its metadata cache: it printed "HDF5: infinite loop
// closing library" and a line of object types (mutation_tools, seed 2908001). Their stderr goes
// to /dev/null from here on.
void end_stderr_after_the_error() {
  std::fflush(stderr);
  const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null < 0) return;
  ::dup2(null, STDERR_FILENO);
  ::close(null);
}
}  // namespace

Activity::Activity(const std::string& what) : previous_(g_activity) { set_activity(what); }
Activity::~Activity() { set_activity(previous_); }

int verbosity() { return g_verbosity; }
void set_verbosity(int v) { g_verbosity = v; }
const std::string& tool_name() { return g_tool; }

void print_line(int min_verbosity, const std::string& prefix, const std::string& text) {
  if (g_verbosity < min_verbosity) return;
  std::fprintf(stderr, "%s: %s%s\n", g_tool.c_str(), prefix.c_str(), text.c_str());
}

Tool::Tool(ToolInfo info) : info_(std::move(info)), app_(info_.summary, info_.name) {
  g_tool = info_.name;
  app_.formatter(std::make_shared<HelpFormatter>(info_.example));
  app_.set_version_flag("--version", std::string(info_.name) + " (ugs) " + version_string);
  app_.add_flag_function("-v,--verbose", [](std::int64_t n) { g_verbosity += static_cast<int>(n); },
                         "More messages on stderr (repeat for more)");
  app_.add_flag_function("-q,--quiet", [](std::int64_t) { g_verbosity = -1; }, "Only errors and warnings on stderr");
}

std::string& Tool::add_output(const std::string& default_path, const std::string& what) {
  output_ = default_path;
  app_.add_option("-o,--output", output_, what + " ('-' = stdout)")->capture_default_str();
  return output_;
}

namespace {
// A line whose place is the setting itself ("setting: ...") or one value of it ("setting VALUE: ...",
// the value without spaces, e.g. "parameter to calibrate material.pool_c.c_R=6:2: ...").
bool names_the_place(const std::string& line, const std::string& setting) {
  if (line.rfind(setting, 0) != 0 || line.size() < setting.size() + 2) return false;
  if (line.compare(setting.size(), 2, ": ") == 0) return true;
  if (line[setting.size()] != ' ') return false;
  const auto colon = line.find(": ", setting.size() + 1);
  return colon != std::string::npos && colon > setting.size() + 1 &&
         line.find(' ', setting.size() + 1) == colon + 1;
}
}  // namespace

std::string Tool::with_flags(std::string line) const {
  for (const auto& [setting, flag] : settings_) {
    if (names_the_place(line, setting)) {
      line = flag + line.substr(setting.size());
    } else if (const auto at = line.find(setting); at != std::string::npos && line.find(flag) == std::string::npos) {
      line.insert(at + setting.size(), " (" + flag + ")");
    }
  }
  return line;
}

int Tool::run(int argc, char** argv, const std::function<void()>& body) {
  for (int i = 0; i < argc; ++i) command_line_ += (i ? " " : "") + quote_arg(argv[i]);
  install_output_cleanup_handlers();
  std::set_terminate(on_terminate);
  try {
    app_.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app_.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app_.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::cout << app_.version() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    for (auto& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "%s: error: %s (see --help)\n", g_tool.c_str(), msg.c_str());
    return 2;
  }
  try {
    body();
    return 0;
  } catch (const InputError& e) {
    // Bad input is one line, also when one pass found several problems (ErrorList: one per
    // line of what()): they follow each other on it, separated by "; ".
    const std::string all = e.what();
    std::string line;
    for (std::size_t p = 0; p <= all.size();) {
      const auto q = std::min(all.find('\n', p), all.size());
      line += (line.empty() ? "" : "; ") + with_flags(all.substr(p, q - p));
      p = q + 1;
    }
    std::fprintf(stderr, "%s: error: %s\n", g_tool.c_str(), line.c_str());
    end_stderr_after_the_error();
    return 2;
  } catch (const ComputeError& e) {
    std::fprintf(stderr, "%s: error: %s\n", g_tool.c_str(), with_flags(e.what()).c_str());
    end_stderr_after_the_error();
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: error: out of memory while %s\n", g_tool.c_str(), g_activity);
    end_stderr_after_the_error();
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: internal error: %s\n", g_tool.c_str(), e.what());
    end_stderr_after_the_error();
    return 1;
  }
}

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), tty_(::isatty(STDERR_FILENO)), start_(now_seconds()), last_print_(start_) {}

Progress::~Progress() {
  if (!finished_ && tty_ && g_verbosity >= 0) std::fputc('\n', stderr);
}

void Progress::update(std::size_t done) {
  if (g_verbosity < 0 || total_ == 0) return;
  const double t = now_seconds();
  if (tty_) {
    if (t - last_print_ < 0.1 && done < total_) return;
    const int width = 30, filled = static_cast<int>(width * done / total_);
    std::fprintf(stderr, "\r%s: %s [%s%s] %zu/%zu", g_tool.c_str(), label_.c_str(), std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), done, total_);
  } else {
    if (t - last_print_ < 5.0) return;
    std::fprintf(stderr, "%s: %s %zu/%zu (%.0f s)\n", g_tool.c_str(), label_.c_str(), done, total_, t - start_);
  }
  last_print_ = t;
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (g_verbosity < 0) return;
  if (tty_) std::fputc('\n', stderr);
  if (g_verbosity >= 1)
    std::fprintf(stderr, "%s: %s done in %.2f s\n", g_tool.c_str(), label_.c_str(), now_seconds() - start_);
}

}  // namespace ugs::cli
