// Shared pieces of the libFuzzer targets (docs/fuzzing.md): a private temporary folder for readers
// that need a file name, and the rule that ugs::InputError / ugs::ComputeError are normal outcomes.
// Any other exception escapes the target, libFuzzer reports it ("deadly signal" after
// std::terminate) and keeps the input as a crash artifact: that is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "ugs/formats/error.hpp"

namespace ugs::fuzz {

// One folder per process (in /dev/shm when there is one), removed at exit.
inline const std::string& temp_dir() {
  struct Dir {
    std::string path;
    // In memory when possible: a file per execution on a busy disk costs more than the reader.
    Dir() : path(((std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                              : std::filesystem::temp_directory_path()) /
                  "ugs-fuzz-XXXXXX").string()) {
      if (!mkdtemp(path.data())) std::abort();
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

// Writes the input to temp_dir()/name and returns the path.
inline std::string write_temp(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = temp_dir() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Runs one reader call; a refusal (InputError) or a failed computation (ComputeError) is a normal
// outcome, returns whether the call succeeded.
template <class F>
bool outcome(F&& f) {
  try {
    f();
    return true;
  } catch (const ugs::InputError&) {
    return false;
  } catch (const ugs::ComputeError&) {
    return false;
  }
}

}  // namespace ugs::fuzz
