// Azure Kinect recordings (.mkv) through AzureKinectReader: the headers, the calibration
// attachment and every capture (colour, depth and IR decoded), as `capture-from` reads them.
#include "fuzz/fuzz_input.h"
#include "simtree/io/azure_kinect.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "recording.mkv");
  return simtree::fuzz::ReadOrRefuse([&] {
    simtree::AzureReaderOptions options;
    options.read_ir = true;
    simtree::AzureKinectReader reader(path, options);
    while (reader.Next()) {
    }
  });
}
