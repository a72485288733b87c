#include "simtree/core/tree_file.h"

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"

namespace simtree {
namespace {

std::string Extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

[[noreturn]] void UnknownExtension(const std::filesystem::path& path) {
  throw InputError(path.string(), "",
                   fmt::format("expected a tree file ending in .json (simtree) or .txt (the "
                               "authors' demo format), got \"{}\"",
                               path.extension().string()));
}

}  // namespace

Tree ReadTreeFile(const std::filesystem::path& path, const TreeFileOptions& options) {
  const std::string ext = Extension(path);
  Tree tree;
  if (ext == ".json") {
    tree = ReadTreeJson(path);
  } else if (ext == ".txt") {
    tree = ReadLegacyTree(path, options.legacy);
  } else {
    UnknownExtension(path);
  }
  if (options.legacy_parameters) ReadLegacyParameters(*options.legacy_parameters, tree);
  return tree;
}

void CheckTreeFilePath(const std::filesystem::path& path) {
  const std::string ext = Extension(path);
  if (ext != ".json" && ext != ".txt") UnknownExtension(path);
}

void WriteTreeFile(const Tree& tree, const std::filesystem::path& path,
                   const TreeFileOptions& options) {
  const std::string ext = Extension(path);
  if (ext == ".json") {
    WriteTreeJson(tree, path);
  } else if (ext == ".txt") {
    WriteLegacyTree(tree, path, options.legacy);
    if (options.legacy_parameters) WriteLegacyParameters(tree, *options.legacy_parameters);
  } else {
    UnknownExtension(path);
  }
}

}  // namespace simtree
