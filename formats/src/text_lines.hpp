// Line-by-line reading of the text formats of horizons (IRAP, CPS-3, GOCAD TSurf): whitespace
// tokens, numbers checked as finite, and "file:line" for every error.
#pragma once
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"

namespace ugs::text {

class Lines {
public:
  Lines(const std::string& path, const std::string& expected) : in_(InputStream::open(path, expected)) {}
  // The next line and its tokens; false at the end of the file.
  bool next() {
    if (!in_->getline(text_)) return false;
    ++line_;
    tokens_.clear();
    std::size_t i = 0;
    while (i < text_.size()) {
      while (i < text_.size() && is_space(text_[i])) ++i;
      const std::size_t b = i;
      while (i < text_.size() && !is_space(text_[i])) ++i;
      if (i > b) tokens_.push_back(std::string_view(text_).substr(b, i - b));
    }
    return true;
  }
  const std::string& text() const { return text_; }
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  std::size_t line() const { return line_; }
  const std::string& name() const { return in_->name(); }
  std::string where() const { return fmt::format("{}:{}", in_->name(), line_); }
  InputError error(const std::string& message) const { return InputError(where(), message); }

private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
  std::unique_ptr<InputStream> in_;
  std::string text_;
  std::vector<std::string_view> tokens_;
  std::size_t line_ = 0;
};

// Printable form of a token for an error message (at most 40 characters, bytes outside ASCII as \xNN).
inline std::string shown(std::string_view t) {
  std::string s;
  for (char c : t.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) s += c;
    else s += fmt::format("\\x{:02x}", u);
  }
  return t.size() > 40 ? s + "..." : s;
}

// A finite number (a leading '+' allowed), or nothing.
inline bool parse_number(std::string_view t, double& v) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(v);
}

inline double number(const Lines& in, std::string_view t, const std::string& what) {
  double v;
  if (!parse_number(t, v)) throw in.error(fmt::format("{}: '{}' is not a finite number", what, shown(t)));
  return v;
}

// A whole number within [lo, hi].
inline long long integer(const Lines& in, std::string_view t, const std::string& what, long long lo, long long hi) {
  double v;
  if (!parse_number(t, v) || v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi))
    throw in.error(fmt::format("{}: '{}' is not a whole number from {} to {}", what, shown(t), lo, hi));
  return static_cast<long long>(v);
}

}  // namespace ugs::text
