#pragma once
// Strict reading of JSON documents: every accessor names the JSON path it failed at, so a bad
// file gives "file: branches[3].nodes[0]: expected 4 numbers [x, y, z, radius], got 3".

#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace simtree {

// Parses `text`; a syntax error becomes InputError with the line and column.
nlohmann::json ParseJson(const std::string& text, const std::string& source);

class JsonReader {
 public:
  explicit JsonReader(std::string source) : source_(std::move(source)) {}
  const std::string& source() const { return source_; }

  // The member `key` of object `obj` found at path `at`; throws when it is missing.
  const nlohmann::json& Field(const nlohmann::json& obj, const std::string& key,
                              const std::string& at) const;
  bool Has(const nlohmann::json& obj, const std::string& key) const;
  double Number(const nlohmann::json& value, const std::string& at) const;
  int Integer(const nlohmann::json& value, const std::string& at) const;
  std::string String(const nlohmann::json& value, const std::string& at) const;
  const nlohmann::json& Array(const nlohmann::json& value, const std::string& at) const;
  const nlohmann::json& Object(const nlohmann::json& value, const std::string& at) const;
  Eigen::Vector3d Vector3(const nlohmann::json& value, const std::string& at) const;
  [[noreturn]] void Fail(const std::string& at, const std::string& message) const;

 private:
  std::string source_;
};

// Path helpers: Member("a", "b") == "a.b", Element("a", 3) == "a[3]".
std::string Member(const std::string& at, const std::string& key);
std::string Element(const std::string& at, size_t index);

}  // namespace simtree
