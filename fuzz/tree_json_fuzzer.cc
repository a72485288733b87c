// The simtree tree file (tree.json, static.json, simready.json) through ReadTreeFile.
#include "fuzz/fuzz_input.h"
#include "simtree/core/tree_file.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = simtree::fuzz::WriteInput(data, size, "tree.json");
  return simtree::fuzz::ReadOrRefuse([&] { simtree::ReadTreeFile(path); });
}
