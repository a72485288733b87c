// The capture folder's other small files: capture.json, pull/init.json and pull/frames.csv. Each
// input is given to all three readers (the corpus holds seeds of each), so one target covers them.
#include "fuzz/fuzz_input.h"
#include "simtree/io/capture.h"
#include "simtree/io/track_init.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace simtree;
  fuzz::ReadOrRefuse([&] { ReadCaptureInfo(fuzz::WriteInput(data, size, "capture.json")); });
  fuzz::ReadOrRefuse([&] { ReadTrackInitJson(fuzz::WriteInput(data, size, "init.json")); });
  return fuzz::ReadOrRefuse([&] { ReadFramesCsv(fuzz::WriteInput(data, size, "frames.csv")); });
}
