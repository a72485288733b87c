// A capture's intrinsics.json (per scan view and of the pull stream).
#include "fuzz/fuzz_input.h"
#include "simtree/io/capture.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "intrinsics.json");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadIntrinsicsJson(path); });
}
