// Typed errors: library code throws, only a tool's main turns them into a one-line
// message and an exit code (2 for bad input or usage, 1 for a failed computation).
#pragma once
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace ugs {

// Bad input or bad usage: the user can fix it. Exit code 2.
class InputError : public std::runtime_error {
public:
  // `where` names the place, e.g. "model.msh:12" or "model.msh: byte 4096"; may be empty.
  InputError(std::string where, const std::string& message)
      : std::runtime_error(where.empty() ? message : where + ": " + message), where_(std::move(where)) {}
  const std::string& where() const { return where_; }

private:
  std::string where_;
};

// Every problem found in one pass over an input (as GMT's parse() counts n_errors): checked in
// full, then thrown as one InputError holding one "where: what" line per problem, in the order of
// the lines they name ("file:LINE"; problems without a line keep their order, after those with
// one); the tool prints them on its one error line, separated by "; " (docs/cli.md).
class ErrorList {
public:
  void add(const std::string& where, const std::string& message) {
    items_.push_back({line_of(where), where.empty() ? message : where + ": " + message});
  }
  void add(const InputError& e) { items_.push_back({line_of(e.where()), e.what()}); }
  std::size_t size() const { return items_.size(); }
  void throw_if_any() const {
    if (items_.empty()) return;
    auto sorted = items_;
    std::stable_sort(sorted.begin(), sorted.end(), [](const Item& a, const Item& b) { return a.line < b.line; });
    std::string text;
    for (const auto& i : sorted) text += (text.empty() ? "" : "\n") + i.text;
    throw InputError("", text);
  }

private:
  struct Item {
    unsigned long line;  // the line named by "file:LINE", or the largest value when none is named
    std::string text;
  };
  static unsigned long line_of(const std::string& where) {
    const auto colon = where.rfind(':');
    if (colon == std::string::npos || colon + 1 == where.size()) return ~0ul;
    unsigned long line = 0;
    for (std::size_t k = colon + 1; k < where.size(); ++k) {
      if (where[k] < '0' || where[k] > '9') return ~0ul;
      line = line * 10 + static_cast<unsigned long>(where[k] - '0');
    }
    return line;
  }
  std::vector<Item> items_;
};

// The computation failed (no convergence, singular system, ...). Exit code 1.
class ComputeError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace ugs
