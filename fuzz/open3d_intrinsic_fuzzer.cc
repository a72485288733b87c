// Open3D's PinholeCameraIntrinsic JSON (a reconstruction folder's intrinsic.json), read as the
// folder reader does and as a user's camera file (either format, told apart by their fields).
#include "fuzz/fuzz_input.h"
#include "simtree/io/intrinsics_file.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace simtree;
  const auto path = fuzz::WriteInput(data, size, "intrinsic.json");
  fuzz::ReadOrRefuse([&] { ReadOpen3dIntrinsicJson(path); });
  return fuzz::ReadOrRefuse([&] { ReadIntrinsicsFile(path); });
}
