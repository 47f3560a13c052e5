// Typed errors: library code throws, only a tool's main turns them into a one-line
// message and an exit code (2 for bad input or usage, 1 for a failed computation).
#pragma once
#include <stdexcept>
#include <string>

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
// full, then thrown as one InputError holding one "where: what" line per problem; the tool prints
// each line as its own error line.
class ErrorList {
public:
  void add(const std::string& where, const std::string& message) {
    text_ += (text_.empty() ? "" : "\n") + (where.empty() ? message : where + ": " + message);
    ++count_;
  }
  std::size_t size() const { return count_; }
  void throw_if_any() const {
    if (count_) throw InputError("", text_);
  }

private:
  std::string text_;
  std::size_t count_ = 0;
};

// The computation failed (no convergence, singular system, ...). Exit code 1.
class ComputeError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace ugs
