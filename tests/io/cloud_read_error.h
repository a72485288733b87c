#pragma once
// The message ReadPointCloud gives for a file it refuses ("" when it reads the file).

#include <filesystem>
#include <string>

#include "simtree/io/point_cloud_io.h"
#include "test_util.h"

namespace simtree::test {

inline std::string CloudReadError(const std::filesystem::path& path) {
  return ErrorOf([&] { ReadPointCloud(path); });
}

}  // namespace simtree::test
