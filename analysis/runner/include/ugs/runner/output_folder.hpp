// A folder of outputs that appears all at once: files are written into a hidden temporary folder
// beside the target, which replaces the target on commit(); without commit (an error was thrown)
// the temporary folder is removed, so a failed run leaves nothing that looks valid.
#pragma once
#include <filesystem>
#include <string>

namespace ugs::runner {

class OutputFolder {
public:
  explicit OutputFolder(const std::string& path);  // InputError if it cannot be created
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& target() const { return target_; }
  // Where to write now: temporary/<name>.
  std::string file(const std::string& name) const { return (tmp_ / name).string(); }
  const std::filesystem::path& temp() const { return tmp_; }
  // Replaces the target (a folder from an earlier run is removed).
  void commit();

private:
  std::filesystem::path target_, tmp_;
  bool committed_ = false;
};

}  // namespace ugs::runner
