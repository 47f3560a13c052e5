// A file or folder removed when the scope ends, whatever happens in it, unless released (it became
// the result): the runner's temporary case copies and run folders leave nothing behind.
#pragma once
#include <filesystem>
#include <system_error>

namespace ugs::runner {

class RemoveAtExit {
public:
  explicit RemoveAtExit(std::filesystem::path p) : path_(std::move(p)) {}
  RemoveAtExit(const RemoveAtExit&) = delete;
  RemoveAtExit& operator=(const RemoveAtExit&) = delete;
  ~RemoveAtExit() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  void release() { path_.clear(); }

private:
  std::filesystem::path path_;
};

}  // namespace ugs::runner
