#include "support/open3d_folder_writer.h"

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/io/image_io.h"

namespace simtree::test {

namespace fs = std::filesystem;

std::string Open3dIntrinsicJson() {
  return R"({"width": 40, "height": 30,
  "intrinsic_matrix": [35.0, 0.0, 0.0, 0.0, 36.0, 0.0, 19.5, 14.5, 1.0]})";
}

fs::path WriteOpen3dFolder(const fs::path& dir, int frames, const std::string& intrinsic_name) {
  fs::create_directories(dir / "color");
  fs::create_directories(dir / "depth");
  for (int i = 0; i < frames; ++i) {
    RgbImage c(kOpen3dWidth, kOpen3dHeight);
    DepthImage d(kOpen3dWidth, kOpen3dHeight);
    for (int y = 0; y < kOpen3dHeight; ++y) {
      for (int x = 0; x < kOpen3dWidth; ++x) {
        c.at(x, y, 0) = static_cast<uint8_t>(x * 6);
        c.at(x, y, 1) = static_cast<uint8_t>(y * 8);
        c.at(x, y, 2) = static_cast<uint8_t>(i * 50);
        d.at(x, y) = static_cast<uint16_t>(2000 + 3 * x + y + 100 * i);
      }
    }
    const std::string name = fmt::format("{:06d}", i);
    WritePng(c, dir / "color" / (name + ".png"));
    WritePng(d, dir / "depth" / (name + ".png"));
  }
  WriteFileAtomically(dir / intrinsic_name, Open3dIntrinsicJson());
  return dir;
}

}  // namespace simtree::test
