#pragma once
// RealSense .bag files (ROS bag 2.0) after the ROS wiki's record layout: records in one chunk
// (uncompressed, lz4, bz2), colour and depth sensor_msgs/Image topics with their
// sensor_msgs/CameraInfo and the Depth Units option, for the bag reader's tests and fuzz seeds.
//
// Colour frame i is (x * 10, y * 20, i * 30) as bgr8 at 1.0 + 0.033 i s; depth is raw
// 1000 + 7x + y (Depth Units 0.0001 m) at 1.035, 1.002 and 1.300 s, written before the colour.

#include <filesystem>
#include <string>

namespace simtree::test {

constexpr int kBagWidth = 16;
constexpr int kBagHeight = 12;

struct BagSpec {
  std::string compression = "none";  // "lz4", "bz2"; "broken": bz2-labelled bytes no one reads
  double depth_fx = 14;              // the colour camera's fx is 14: equal means registered
  int depth_width = kBagWidth;
};

// Whether this build of the writer can compress so ("none" and "broken" always).
bool BagCompressionWritten(const std::string& compression);

std::string BagBytes(const BagSpec& spec);
std::filesystem::path WriteBag(const std::filesystem::path& path, const BagSpec& spec = {});

}  // namespace simtree::test
