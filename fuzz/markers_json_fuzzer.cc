// pull/markers.json (simtree.markers): the marker links a user writes down.
#include "fuzz/fuzz_input.h"
#include "simtree/io/capture.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "markers.json");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadMarkersJson(path); });
}
