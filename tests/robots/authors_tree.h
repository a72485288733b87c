#pragma once
// The paper's demo tree01 with its materials (../shared/data/authors-demo).

#include "simtree/core/tree.h"
#include "simtree/core/tree_file.h"
#include "test_util.h"

namespace simtree::test {

inline Tree AuthorsTree01() {
  TreeFileOptions options;
  options.legacy_parameters = SharedData("authors-demo/tree_parameters.txt");
  return ReadTreeFile(SharedData("authors-demo/tree_model/tree01.txt"), options);
}

}  // namespace simtree::test
