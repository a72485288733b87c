#pragma once
// Reading and writing a tree by file name: .json is the simtree format, .txt the authors' demo
// format (with an optional tree_parameters.txt for materials).

#include <filesystem>
#include <optional>

#include "simtree/core/legacy_format.h"
#include "simtree/core/tree.h"

namespace simtree {

struct TreeFileOptions {
  LegacyOptions legacy;                                    // for .txt files
  std::optional<std::filesystem::path> legacy_parameters;  // tree_parameters.txt to apply
};

Tree ReadTreeFile(const std::filesystem::path& path, const TreeFileOptions& options = {});
// .json or .txt (the latter writes `legacy_parameters` too when set and the tree has materials).
// Throws InputError naming `path` for another extension (CheckTreeFilePath, before any work).
void CheckTreeFilePath(const std::filesystem::path& path);
void WriteTreeFile(const Tree& tree, const std::filesystem::path& path,
                   const TreeFileOptions& options = {});

}  // namespace simtree
