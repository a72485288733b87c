#include "support/tum_rgbd_writer.h"

#include <string>
#include <vector>

#include "simtree/core/atomic_file.h"

namespace simtree::test {

namespace fs = std::filesystem;

RgbImage TumColor(int frame) {
  RgbImage c(kTumWidth, kTumHeight);
  for (int y = 0; y < kTumHeight; ++y) {
    for (int x = 0; x < kTumWidth; ++x) {
      c.at(x, y, 0) = static_cast<uint8_t>(x * 8);
      c.at(x, y, 1) = static_cast<uint8_t>(y * 8);
      c.at(x, y, 2) = static_cast<uint8_t>(frame * 40);
    }
  }
  return c;
}

DepthImage TumRawDepth(int width, int height) {
  DepthImage d(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) d.at(x, y) = static_cast<uint16_t>(5 * (1000 + x + 10 * y));
  }
  return d;
}

fs::path WriteTumSequence(const fs::path& dir) {
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  const std::vector<std::string> rgb_t = {"10.000000", "10.033000", "10.067000", "10.100000"};
  const std::vector<std::string> depth_t = {"10.005000", "10.040000", "10.070000", "10.300000"};
  std::string rgb = "# color images\n# timestamp filename\n";
  std::string depth = "# depth maps\n# timestamp filename\n";
  for (size_t i = 0; i < rgb_t.size(); ++i) {
    WritePng(TumColor(static_cast<int>(i)), dir / "rgb" / (rgb_t[i] + ".png"));
    WritePng(TumRawDepth(), dir / "depth" / (depth_t[i] + ".png"));
    rgb += rgb_t[i] + " rgb/" + rgb_t[i] + ".png\n";
    depth += depth_t[i] + " depth/" + depth_t[i] + ".png\n";
  }
  WriteFileAtomically(dir / "rgb.txt", rgb);
  WriteFileAtomically(dir / "depth.txt", depth);
  return dir;
}

}  // namespace simtree::test
