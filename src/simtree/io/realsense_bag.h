#pragma once
// RealSense recordings (.bag: ROS bag 2.0, what the RealSense Viewer and `rs-record` write), read
// without ROS or librealsense: the colour and depth image topics (sensor_msgs/Image), their camera
// info (sensor_msgs/CameraInfo) and the depth units option. Colour and depth are paired by their
// header stamps within a tolerance. The depth must already be registered to the colour (same size
// and camera, as an aligned recording is): depth in the depth camera's own view is refused, not
// reprojected. Chunks compressed with lz4 or bz2 are read when simtree was built with liblz4 /
// libbz2 (src/simtree/io/CMakeLists.txt finds them), refused with a message otherwise.
//
//   const std::unique_ptr<RgbdSequence> seq = OpenRealSenseBag("pull.bag", {});

#include <filesystem>
#include <memory>
#include <optional>

#include "simtree/io/rgbd_sequence.h"

namespace simtree {

struct RealSenseBagOptions {
  double max_time_difference_s = 0.02;      // colour-depth pairing tolerance
  std::optional<double> depth_units_per_m;  // else the bag's "Depth Units" option, else 1000
  void Validate() const;
};

// True for a file ending in .bag.
bool IsRosBagFile(const std::filesystem::path& path);

// Throws InputError naming the file (and topic or byte) when it is not a ROS bag 2.0, has no
// colour or depth image topic or no camera info, an unsupported encoding, chunks it cannot
// decompress,
// depth not registered to colour, or no colour-depth pair within the tolerance.
std::unique_ptr<RgbdSequence> OpenRealSenseBag(const std::filesystem::path& path,
                                               const RealSenseBagOptions& options);

}  // namespace simtree
