// An Azure Kinect recording's calibration.json attachment, scaled to the NFOV unbinned depth
// mode and 720p colour (the shared recording's modes).
#include <string>

#include "fuzz/fuzz_input.h"
#include "simtree/io/azure_kinect.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  return simtree::fuzz::ReadOrRefuse(
      [&] { simtree::ParseAzureCalibration(text, "calibration.json", 640, 576, 1280, 720); });
}
