#pragma once
// Outputs that appear whole or not at all: write to a temporary beside the target, then rename.
// Also the guard that an output never replaces one of the inputs.

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace simtree {

// A file written through a temporary in the same folder. Commit() renames it into place; if the
// object dies without Commit() (an exception on the way), the temporary is removed and the target
// is untouched.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target, bool binary = false);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return stream_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }
  // Flushes, checks the stream and renames the temporary onto the target. Throws IoError.
  void Commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream stream_;
  bool committed_ = false;
};

// Writes `bytes` to `target` atomically.
void WriteFileAtomically(const std::filesystem::path& target, const std::string& bytes);

// A folder filled through a staging folder beside it; Commit() swaps it into place (replacing an
// older output folder of the same name), and an uncommitted staging folder is removed.
class AtomicDirectory {
 public:
  explicit AtomicDirectory(std::filesystem::path target);
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  // Where to write the folder's contents until Commit().
  const std::filesystem::path& path() const { return staging_; }
  void Commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

// Throws InputError when `output` is (or is inside, for a folder) one of `inputs`.
void RefuseToOverwriteInputs(const std::filesystem::path& output,
                             const std::vector<std::filesystem::path>& inputs);

// Reads a whole file; throws IoError naming it when it cannot.
std::string ReadFile(const std::filesystem::path& path);

}  // namespace simtree
