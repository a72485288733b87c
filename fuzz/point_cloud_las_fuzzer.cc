// LAS point clouds (versions 1.0-1.4, point formats 0-3 and 6-8), simtree's own reader.
#include "fuzz/fuzz_input.h"
#include "simtree/io/point_cloud_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "cloud.las");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadPointCloud(path); });
}
