#pragma once
// The exceptions simtree throws. Every message names where the problem is (file, line, field,
// frame) and what was expected, so the CLI can print it as is and exit non-zero.

#include <stdexcept>
#include <string>

namespace simtree {

// Base of every simtree exception; `exit_code()` is what the CLI returns for it.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, int exit_code = 1)
      : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

// Input that does not meet its specification: `source` is the file (or "<memory>"), `where` the
// line, field or frame ("line 12", "branches[3].nodes[0].radius"), `message` what was expected.
class InputError : public Error {
 public:
  InputError(const std::string& source, const std::string& where, const std::string& message)
      : Error(Format(source, where, message)), source_(source), where_(where) {}
  const std::string& source() const { return source_; }
  const std::string& where() const { return where_; }

 private:
  static std::string Format(const std::string& source, const std::string& where,
                            const std::string& message) {
    std::string out = source;
    if (!where.empty()) out += (out.empty() ? "" : ": ") + where;
    return out.empty() ? message : out + ": " + message;
  }
  std::string source_;
  std::string where_;
};

// A file that cannot be opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
};

// A stage of the pipeline that is not built yet (the CLI exits 2 for it).
class NotBuiltError : public Error {
 public:
  explicit NotBuiltError(const std::string& message) : Error(message, 2) {}
};

}  // namespace simtree
