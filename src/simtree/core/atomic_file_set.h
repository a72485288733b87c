#pragma once
// Several output files that appear together or not at all, for verbs that write more than one
// file (a tree, its mesh, its picture): each is written to a temporary beside its target, and
// only when every one is written are they renamed into place.

#include <filesystem>
#include <vector>

namespace simtree {

class AtomicFileSet {
 public:
  AtomicFileSet() = default;
  ~AtomicFileSet();  // removes every temporary not committed; the targets stay as they were
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;

  // The path to write `target` to until Commit(): beside it, with its extension (writers that
  // choose the format by extension write the right one). Throws IoError when `target` is a folder
  // or its folder cannot be made, before any work is spent on it.
  std::filesystem::path Stage(const std::filesystem::path& target);
  // Renames every staged file onto its target, in the order staged. Throws IoError naming the
  // target whose temporary is missing (never written) before renaming any.
  void Commit();

 private:
  struct Entry {
    std::filesystem::path target, temporary;
  };
  std::vector<Entry> entries_;
  bool committed_ = false;
};

}  // namespace simtree
