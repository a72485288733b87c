// RealSense .bag recordings (ROS bag 2.0, chunks plain, lz4 or bz2): the bag opened as a sequence
// and every colour-depth pair decoded, as capture-from does.
#include "fuzz/fuzz_input.h"
#include "simtree/io/realsense_bag.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "recording.bag");
  return simtree::fuzz::ReadOrRefuse([&] {
    const auto sequence = simtree::OpenRealSenseBag(path, {});
    for (size_t i = 0; i < sequence->size(); ++i) sequence->Load(i);
  });
}
