// Byte streams for tools: a buffered input that never seeks (works on pipes) and knows where it
// is (line and byte offset, for one-line errors), and an atomic output (temporary file + rename,
// "-" means stdout) so a failed run leaves nothing that looks valid.
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ugs/formats/error.hpp"

namespace ugs {

class InputStream {
public:
  // Opens `path`; "-" or "" means stdin. Throws InputError if it cannot be opened or is a directory
  // ("model.msh: is a directory (expected an MSH file)": `expected` names the kind of file).
  static std::unique_ptr<InputStream> open(const std::string& path, const std::string& expected = "a file");
  // Wraps an in-memory buffer (tests).
  static std::unique_ptr<InputStream> from_string(std::string data, std::string name);
  ~InputStream();
  InputStream(const InputStream&) = delete;
  InputStream& operator=(const InputStream&) = delete;

  const std::string& name() const { return name_; }
  // Total size when the input is a regular file (or a buffer); nullopt for pipes.
  std::optional<std::uint64_t> size() const { return size_; }
  std::optional<std::uint64_t> remaining() const;
  std::uint64_t offset() const { return offset_; }
  std::size_t line() const { return line_; }

  // Reads one line without its end-of-line; false at end of input.
  bool getline(std::string& out);
  // Reads exactly n bytes or throws a truncation error.
  void read_exact(void* dst, std::size_t n);
  // Next byte without consuming it; -1 at end of input.
  int peek();
  // Skips spaces, tabs and newlines (line count kept).
  void skip_whitespace();
  // Next whitespace-separated token; empty at end of input.
  std::string_view token();

  // Errors that name this input and the current line / byte offset.
  InputError error(const std::string& message) const;
  InputError error_at_byte(const std::string& message) const;

private:
  InputStream() = default;
  bool fill();
  std::FILE* file_ = nullptr;
  bool owns_file_ = false;
  std::string name_;
  std::optional<std::uint64_t> size_;
  std::vector<char> buf_;
  std::size_t pos_ = 0, end_ = 0;
  std::uint64_t offset_ = 0;
  std::size_t line_ = 1;
  std::string token_;
  bool eof_ = false;
};

// Output written atomically: to a temporary file beside `path`, renamed on commit().
// Destroyed without commit (an error was thrown), the temporary is removed. "-" writes to stdout.
class OutputFile {
public:
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::FILE* stream() { return file_; }
  const std::string& path() const { return path_; }
  bool is_stdout() const { return to_stdout_; }
  // The temporary file being written ("" for stdout), for libraries that open files by name (HDF5):
  // they write there, close it, then commit() renames it.
  const std::string& temp_path() const { return tmp_; }
  void write(const void* data, std::size_t n);
  void write(std::string_view s) { write(s.data(), s.size()); }
  void commit();

private:
  std::string path_, tmp_;
  std::FILE* file_ = nullptr;
  bool to_stdout_ = false, committed_ = false;
};

// Removes every uncommitted temporary output on SIGINT/SIGTERM/SIGPIPE (installed by the CLI layer).
void install_output_cleanup_handlers();
// Removes every uncommitted temporary output now (async-signal-safe: for std::terminate handlers).
void remove_uncommitted_outputs();

}  // namespace ugs
