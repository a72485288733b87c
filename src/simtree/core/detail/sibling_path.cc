#include "simtree/core/detail/sibling_path.h"

#include <unistd.h>

#include <atomic>

#include <fmt/format.h>

namespace fs = std::filesystem;

namespace simtree::detail {

fs::path SiblingName(const fs::path& target, const char* tag) {
  static std::atomic<int> counter{0};
  return target.parent_path() / fmt::format(".{}.{}-{}-{}{}", target.stem().string(), tag,
                                            ::getpid(), counter++, target.extension().string());
}

fs::path ParentOrCurrent(const fs::path& path) {
  return path.parent_path().empty() ? fs::path(".") : path.parent_path();
}

}  // namespace simtree::detail
