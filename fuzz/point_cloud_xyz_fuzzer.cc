// Text point clouds (.xyz; .txt and .pts share the parser), parsed by simtree.
#include "fuzz/fuzz_input.h"
#include "simtree/io/point_cloud_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "cloud.xyz");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadPointCloud(path); });
}
