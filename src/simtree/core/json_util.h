#pragma once
// Strict reading of JSON documents. A JsonNode is a value together with its file and its path in
// the document, so a reader names each field once and a bad file gives
// "file: branches[3].nodes[0]: expected 4 numbers [x, y, z, radius], got 3".
//
//   const JsonNode doc = ParseJsonFile(path);
//   CheckFormat(doc, "simtree.pull_load", 1);
//   load.force_n = doc.Number("force_n");                  // required: missing -> InputError
//   if (auto label = doc.Find("label")) m.label = label->String();
//   for (const JsonNode& view : doc.Field("views").Items()) names.push_back(view.String("name"));

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace simtree {

// Parses `text`; a syntax error becomes InputError with the line and column.
nlohmann::json ParseJson(const std::string& text, const std::string& source);

// Path helpers: Member("a", "b") == "a.b", Element("a", 3) == "a[3]".
std::string Member(const std::string& at, const std::string& key);
std::string Element(const std::string& at, size_t index);

class JsonNode {
 public:
  // `value` must outlive the node and every node reached from it.
  JsonNode(const nlohmann::json& value, std::string source, std::string at = "");

  const nlohmann::json& json() const { return *value_; }
  const std::string& source() const { return source_; }
  const std::string& at() const { return at_; }
  bool is_null() const { return value_->is_null(); }

  // Members of an object (the node must be one). Field throws when `key` is missing; Find gives
  // nothing when it is missing or null.
  JsonNode Field(const std::string& key) const;
  std::optional<JsonNode> Find(const std::string& key) const;
  bool Has(const std::string& key) const;

  // Elements of an array (the node must be one).
  size_t size() const;
  JsonNode Item(size_t index) const;
  std::vector<JsonNode> Items() const;

  // The value as a finite number, an int, a string, a bool, or [x, y, z].
  double Number() const;
  int Integer() const;
  std::string String() const;
  bool Bool() const;
  Eigen::Vector3d Vector3() const;
  // Shorthands for a required member: Number("f") == Field("f").Number().
  double Number(const std::string& key) const { return Field(key).Number(); }
  int Integer(const std::string& key) const { return Field(key).Integer(); }
  std::string String(const std::string& key) const { return Field(key).String(); }
  bool Bool(const std::string& key) const { return Field(key).Bool(); }
  Eigen::Vector3d Vector3(const std::string& key) const { return Field(key).Vector3(); }

  // Throws unless the node is an object / an array.
  const JsonNode& ExpectObject() const;
  const JsonNode& ExpectArray() const;
  // InputError naming the file and this node's path (or `at`).
  [[noreturn]] void Fail(const std::string& message) const;
  [[noreturn]] void FailAt(const std::string& at, const std::string& message) const;

 private:
  const nlohmann::json* value_;
  std::string source_;
  std::string at_;
};

// The document of a JSON file, parsed (errors name the file, line and column).
struct JsonDocument {
  nlohmann::json value;
  std::string source;
  JsonNode root() const { return JsonNode(value, source); }
};
JsonDocument ReadJsonDocument(const std::filesystem::path& path);

// Checks the document's "format" and "version" members.
void CheckFormat(const JsonNode& doc, const std::string& format, int version);

}  // namespace simtree
