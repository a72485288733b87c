// materials.json (simtree.materials), what `identify` writes and `build` reads.
#include "fuzz/fuzz_input.h"
#include "simtree/identification/materials_file.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "materials.json");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::identification::ReadMaterialsJson(path); });
}
