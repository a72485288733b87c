// The authors' tree_parameters.txt, applied to a fixed 4-branch demo tree through ReadTreeFile
// (as `simtree convert tree.txt --parameters tree_parameters.txt` reads them).
#include <cstdlib>
#include <fstream>

#include "fuzz/fuzz_input.h"
#include "simtree/core/tree_file.h"

namespace {

// A trunk with two children, one of which has a child: the demo format, 4 branches.
constexpr const char* kTree =
    "RowMax=4\n"
    "0 3 2 red\n1 1\n2 2\n0 0 0 0.4\n0 4 0 0.3\n0 8 0 0.2\n"
    "1 2 1 green\n3 1\n0 4 0 0.1\n2 6 0 0.05\n"
    "2 2 0 green\n0 8 0 0.1\n-2 10 0 0.05\n"
    "3 2 0 blue\n2 6 0 0.03\n3 7 1 0.02\n";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  simtree::fuzz::Quiet();
  std::ofstream(simtree::fuzz::ScratchDir() / "tree.txt") << kTree;
  // The fixed tree must read, or every input would stop at it and nothing would be fuzzed.
  if (simtree::ReadTreeFile(simtree::fuzz::ScratchDir() / "tree.txt").size() != 4) std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  simtree::TreeFileOptions options;
  options.legacy_parameters = simtree::fuzz::WriteInput(data, size, "tree_parameters.txt");
  return simtree::fuzz::ReadOrRefuse(
      [&] { simtree::ReadTreeFile(simtree::fuzz::ScratchDir() / "tree.txt", options); });
}
