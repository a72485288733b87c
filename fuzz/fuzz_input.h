#pragma once
// What every fuzz target shares: the input written to a scratch file (the readers take paths),
// quiet logging, and the rule the targets check: a reader either returns or throws a
// simtree::Error. Any other exception escapes LLVMFuzzerTestOneInput, and libFuzzer reports it
// as a crash with the input that caused it, like a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "simtree/core/error.h"

namespace simtree::fuzz {

// A folder of this process's own under $TMPDIR (or /tmp), made on first use and removed at exit.
const std::filesystem::path& ScratchDir();

// Writes the input to ScratchDir()/name (replacing the last input) and returns the path.
std::filesystem::path WriteInput(const uint8_t* data, size_t size, const std::string& name);

// Silences spdlog and Open3D: a warning per input would cost more than the parsing.
void Quiet();

// Runs `read`; an input the reader refuses with a simtree::Error is a correct answer.
template <typename Read>
int ReadOrRefuse(Read&& read) {
  try {
    read();
  } catch (const simtree::Error&) {
  }
  return 0;
}

}  // namespace simtree::fuzz
