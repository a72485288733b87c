#pragma once
// Temporaries beside an output (AtomicFile, AtomicDirectory, AtomicFileSet).

#include <filesystem>

namespace simtree::detail {

// A hidden name beside `target`, tagged ("partial", "staged", "old"), that no other writer
// (thread or process) uses at the same time. Keeps the extension so libraries that pick a format
// by extension (Open3D) write the right one.
std::filesystem::path SiblingName(const std::filesystem::path& target, const char* tag);

// The folder `path` is in ("." for a bare file name).
std::filesystem::path ParentOrCurrent(const std::filesystem::path& path);

}  // namespace simtree::detail
