#include "fuzz/fuzz_input.h"

#include <cstdlib>
#include <fstream>
#include <system_error>

#include <open3d/utility/Logging.h>
#include <spdlog/spdlog.h>

namespace fs = std::filesystem;

namespace simtree::fuzz {
namespace {

fs::path MakeScratchDir() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/simtree-fuzz-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) std::abort();
  return pattern;
}

}  // namespace

const fs::path& ScratchDir() {
  static const fs::path dir = [] {
    fs::path made = MakeScratchDir();
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(ScratchDir(), ignored);
    });
    return made;
  }();
  return dir;
}

fs::path WriteInput(const uint8_t* data, size_t size, const std::string& name) {
  const fs::path path = ScratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) std::abort();  // the scratch disk is full: not the reader's fault
  return path;
}

void Quiet() {
  spdlog::set_level(spdlog::level::off);
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
}

}  // namespace simtree::fuzz
