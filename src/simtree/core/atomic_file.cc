#include "simtree/core/atomic_file.h"

#include <sstream>

#include <fmt/format.h>

#include "simtree/core/detail/sibling_path.h"
#include "simtree/core/error.h"

namespace fs = std::filesystem;

namespace simtree {

using detail::ParentOrCurrent;
using detail::SiblingName;

AtomicFile::AtomicFile(fs::path target, bool binary) : target_(std::move(target)) {
  const fs::path folder = ParentOrCurrent(target_);
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw IoError(fmt::format("{}: cannot create folder: {}", folder.string(), ec.message()));
  temporary_ = SiblingName(target_, "partial");
  stream_.open(temporary_, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if (!stream_) throw IoError(fmt::format("{}: cannot open for writing", target_.string()));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    stream_.close();
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void AtomicFile::Commit() {
  stream_.flush();
  const bool ok = static_cast<bool>(stream_);
  stream_.close();
  if (!ok) throw IoError(fmt::format("{}: write failed (disk full?)", target_.string()));
  std::error_code ec;
  fs::rename(temporary_, target_, ec);
  if (ec)
    throw IoError(fmt::format("{}: cannot rename into place: {}", target_.string(), ec.message()));
  committed_ = true;
}

void WriteFileAtomically(const fs::path& target, const std::string& bytes) {
  AtomicFile file(target, /*binary=*/true);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.Commit();
}

AtomicDirectory::AtomicDirectory(fs::path target) : target_(std::move(target)) {
  if (target_.filename().empty()) target_ = target_.parent_path();  // "out/" -> "out"
  std::error_code ec;
  fs::create_directories(ParentOrCurrent(target_), ec);
  staging_ = SiblingName(target_, "partial");
  fs::create_directories(staging_, ec);
  if (ec)
    throw IoError(fmt::format("{}: cannot create folder: {}", staging_.string(), ec.message()));
}

AtomicDirectory::~AtomicDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void AtomicDirectory::Commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(target_)) {
    if (!fs::is_directory(target_)) {
      throw IoError(fmt::format("{}: exists and is not a folder", target_.string()));
    }
    old = SiblingName(target_, "old");
    fs::rename(target_, old, ec);
    if (ec) throw IoError(fmt::format("{}: cannot replace: {}", target_.string(), ec.message()));
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, target_);
    throw IoError(fmt::format("{}: cannot rename into place: {}", target_.string(), ec.message()));
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

void RefuseToOverwriteInputs(const fs::path& output, const std::vector<fs::path>& inputs) {
  std::error_code ec;
  const fs::path out = fs::weakly_canonical(output, ec);
  for (const fs::path& input : inputs) {
    const fs::path in = fs::weakly_canonical(input, ec);
    const bool same = out == in;
    // An output folder that would contain (and so replace) an input.
    auto rel = in.lexically_relative(out);
    const bool inside = !rel.empty() && rel.native().rfind("..", 0) != 0 && out != in;
    if (same || inside) {
      throw InputError(output.string(), "",
                       fmt::format("refusing to write over the input {}; choose another output",
                                   input.string()));
    }
  }
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw IoError(fmt::format("{}: cannot open ({})", path.string(),
                              fs::exists(path) ? "permission denied?" : "no such file"));
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace simtree
