// PNG images through simtree's loaders (OpenCV's decoder): each input read as a depth image
// (16-bit millimetres) and as a colour image.
#include "fuzz/fuzz_input.h"
#include "simtree/io/image_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "image.png");
  simtree::fuzz::ReadOrRefuse([&] { simtree::ReadDepthImage(path); });
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadColorImage(path); });
}
