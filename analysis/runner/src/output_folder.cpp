#include "ugs/runner/output_folder.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::runner {

namespace fs = std::filesystem;

OutputFolder::OutputFolder(const std::string& path) : target_(path) {
  if (path.empty() || path == "-") throw InputError("-o", "the outputs are a folder: give its name");
  while (target_.has_filename() == false && target_.has_parent_path() && target_ != target_.parent_path())
    target_ = target_.parent_path();  // "out/" -> "out"
  std::error_code ec;
  if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
    throw InputError(path, "exists and is not a folder");
  const fs::path parent = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  std::string name = target_.filename().string();
  name.insert(0, 1, '.');
  name.append(".tmp-XXXXXX");
  std::string tmpl = (parent / name).string();
  if (!::mkdtemp(tmpl.data())) throw InputError(path, fmt::format("cannot create a folder beside it in {}", parent.string()));
  tmp_ = tmpl;
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(tmp_, ec);
}

void OutputFolder::commit() {
  std::error_code ec;
  fs::permissions(tmp_, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                            fs::perms::others_exec, ec);
  fs::path old;
  if (fs::exists(target_, ec)) {
    old = tmp_;
    old += ".old";
    fs::rename(target_, old, ec);
    if (ec) throw ComputeError(fmt::format("{}: cannot replace the existing folder: {}", target_.string(), ec.message()));
  }
  fs::rename(tmp_, target_, ec);
  if (ec) throw ComputeError(fmt::format("{}: cannot move the outputs into place: {}", target_.string(), ec.message()));
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace ugs::runner
