// The first argument of a case writer is the folder it writes: missing, or an option in its place
// (--help would become a folder), it is refused with the usage line.
#pragma once
#include <cstdio>
#include <optional>
#include <string>

namespace ugs::testcase {

// The exit code to end with (0 for --help or -h, 2 otherwise), or nothing when argv[1] is a folder.
inline std::optional<int> refuse_dir_argument(int argc, char** argv, const char* usage) {
  if (argc >= 2 && argv[1][0] != '-') return std::nullopt;
  std::fprintf(stderr, "usage: %s\n", usage);
  return argc >= 2 && (argv[1] == std::string("--help") || argv[1] == std::string("-h")) ? 0 : 2;
}

}  // namespace ugs::testcase
