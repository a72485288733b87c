// PLY point clouds (ASCII and binary), read through Open3D behind simtree's checks.
#include "fuzz/fuzz_input.h"
#include "simtree/io/point_cloud_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "cloud.ply");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadPointCloud(path); });
}
