#pragma once
// The simtree tree file: versioned JSON ("format": "simtree.tree", "version": 1).
// Schema: docs/schema/simtree.tree.schema.json; prose: docs/formats.md.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "simtree/core/tree.h"
#include "simtree/core/validate.h"

namespace simtree {

inline constexpr const char* kTreeFormat = "simtree.tree";
inline constexpr int kTreeFormatVersion = 1;

// Converts a parsed document; `source` names it in errors. Missing frames are computed from the
// geometry. The result is validated (InputError on the first problem).
Tree TreeFromJson(const nlohmann::json& doc, const std::string& source,
                  const ValidationOptions& validation = {});
nlohmann::ordered_json TreeToJson(const Tree& tree);

Tree ReadTreeJson(const std::filesystem::path& path, const ValidationOptions& validation = {});
// Validates, then writes atomically (no partial file on failure).
void WriteTreeJson(const Tree& tree, const std::filesystem::path& path);

// Enum names as they appear in the file.
ModeKind ParseModeKind(const std::string& name, const std::string& source, const std::string& at);
MaterialSource ParseMaterialSource(const std::string& name, const std::string& source,
                                   const std::string& at);

}  // namespace simtree
