#include "simtree/core/atomic_file_set.h"

#include <fmt/format.h>

#include "simtree/core/detail/sibling_path.h"
#include "simtree/core/error.h"

namespace fs = std::filesystem;

namespace simtree {

AtomicFileSet::~AtomicFileSet() {
  if (committed_) return;
  std::error_code ec;
  for (const Entry& e : entries_) fs::remove(e.temporary, ec);
}

fs::path AtomicFileSet::Stage(const fs::path& target) {
  std::error_code ec;
  if (fs::is_directory(target, ec)) {
    throw IoError(fmt::format("{}: is a folder; expected a file to write", target.string()));
  }
  const fs::path folder = detail::ParentOrCurrent(target);
  fs::create_directories(folder, ec);
  if (ec) throw IoError(fmt::format("{}: cannot create folder: {}", folder.string(), ec.message()));
  const fs::path temporary = detail::SiblingName(target, "staged");
  entries_.push_back({target, temporary});
  return temporary;
}

void AtomicFileSet::Commit() {
  std::error_code ec;
  for (const Entry& e : entries_) {
    if (!fs::is_regular_file(e.temporary, ec)) {
      throw IoError(fmt::format("{}: was not written", e.target.string()));
    }
  }
  for (const Entry& e : entries_) {
    fs::rename(e.temporary, e.target, ec);
    if (ec) {
      throw IoError(
          fmt::format("{}: cannot rename into place: {}", e.target.string(), ec.message()));
    }
  }
  committed_ = true;
}

}  // namespace simtree
