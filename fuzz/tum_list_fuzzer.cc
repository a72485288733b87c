// TUM RGB-D lists in a sequence folder whose images are the seeds'
// (tests/support/tum_rgbd_writer.h, written once at start): each input is read as rgb.txt beside
// the sequence's depth.txt, then as depth.txt beside its rgb.txt, so lines naming the images reach
// the pairing and the first pair is decoded.
#include <string>

#include "fuzz/fuzz_input.h"
#include "simtree/core/atomic_file.h"
#include "simtree/io/tum_rgbd.h"
#include "support/tum_rgbd_writer.h"

namespace {

using simtree::fuzz::ScratchDir;

const simtree::TumRgbdOptions& Options() {
  static const simtree::TumRgbdOptions options = [] {
    simtree::TumRgbdOptions o;
    o.intrinsics = simtree::CameraIntrinsics{
        simtree::test::kTumWidth, simtree::test::kTumHeight, 27, 27, 16, 12, 0.001};
    return o;
  }();
  return options;
}

// The sequence's own list, put back after the other was read.
const std::string& Original(const std::string& name) {
  static const std::string rgb = simtree::ReadFile(ScratchDir() / "rgb.txt");
  static const std::string depth = simtree::ReadFile(ScratchDir() / "depth.txt");
  return name == "rgb.txt" ? rgb : depth;
}

void ReadWithList(const uint8_t* data, size_t size, const std::string& name,
                  const std::string& other) {
  const std::string& keep = Original(other);
  simtree::fuzz::WriteInput(reinterpret_cast<const uint8_t*>(keep.data()), keep.size(), other);
  simtree::fuzz::WriteInput(data, size, name);
  simtree::fuzz::ReadOrRefuse([&] {
    const auto sequence = simtree::OpenTumRgbd(ScratchDir(), Options());
    if (sequence->size() > 0) sequence->Load(0);
  });
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  simtree::test::WriteTumSequence(ScratchDir());
  Original("rgb.txt");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ReadWithList(data, size, "rgb.txt", "depth.txt");
  ReadWithList(data, size, "depth.txt", "rgb.txt");
  return 0;
}
