// trajectories.csv (simtree.trajectories): what `track` writes and `identify` reads.
#include "fuzz/fuzz_input.h"
#include "simtree/io/trajectories.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "trajectories.csv");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadTrajectoriesCsv(path); });
}
