#include "simtree/core/json_util.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"

namespace simtree {
namespace {

std::string TypeName(const nlohmann::json& v) { return v.type_name(); }

}  // namespace

nlohmann::json ParseJson(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // Turn the byte offset into a line and column a person can go to.
    size_t line = 1, column = 1;
    const size_t end = std::min<size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    for (size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string what = e.what();
    const size_t cut = what.find("syntax error");
    if (cut != std::string::npos) what = what.substr(cut);
    throw InputError(source, fmt::format("line {}, column {}", line, column),
                     text.empty() ? "expected a JSON document, the file is empty"
                                  : fmt::format("invalid JSON ({})", what));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond a double's range ("1E4444"): the parser gives no position for it.
    std::string what = e.what();
    const size_t cut = what.find("] ");
    if (cut != std::string::npos) what = what.substr(cut + 2);
    throw InputError(source, "", fmt::format("invalid JSON ({})", what));
  }
}

std::string Member(const std::string& at, const std::string& key) {
  return at.empty() ? key : at + "." + key;
}

std::string Element(const std::string& at, size_t index) {
  return fmt::format("{}[{}]", at, index);
}

JsonNode::JsonNode(const nlohmann::json& value, std::string source, std::string at)
    : value_(&value), source_(std::move(source)), at_(std::move(at)) {}

void JsonNode::Fail(const std::string& message) const { FailAt(at_, message); }

void JsonNode::FailAt(const std::string& at, const std::string& message) const {
  throw InputError(source_, at, message);
}

const JsonNode& JsonNode::ExpectObject() const {
  if (!value_->is_object()) Fail(fmt::format("expected an object, got {}", TypeName(*value_)));
  return *this;
}

const JsonNode& JsonNode::ExpectArray() const {
  if (!value_->is_array()) Fail(fmt::format("expected an array, got {}", TypeName(*value_)));
  return *this;
}

bool JsonNode::Has(const std::string& key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::Field(const std::string& key) const {
  ExpectObject();
  const auto it = value_->find(key);
  if (it == value_->end()) FailAt(Member(at_, key), "missing (required field)");
  return JsonNode(*it, source_, Member(at_, key));
}

std::optional<JsonNode> JsonNode::Find(const std::string& key) const {
  if (!Has(key)) return std::nullopt;
  return JsonNode((*value_)[key], source_, Member(at_, key));
}

size_t JsonNode::size() const { return ExpectArray().value_->size(); }

JsonNode JsonNode::Item(size_t index) const {
  if (index >= size()) {
    Fail(fmt::format("expected at least {} elements, got {}", index + 1, value_->size()));
  }
  return JsonNode((*value_)[index], source_, Element(at_, index));
}

std::vector<JsonNode> JsonNode::Items() const {
  std::vector<JsonNode> items;
  items.reserve(size());
  for (size_t i = 0; i < value_->size(); ++i) items.push_back(Item(i));
  return items;
}

double JsonNode::Number() const {
  if (!value_->is_number()) Fail(fmt::format("expected a number, got {}", TypeName(*value_)));
  const double x = value_->get<double>();
  if (!std::isfinite(x)) Fail("expected a finite number");
  return x;
}

int JsonNode::Integer() const {
  if (!value_->is_number_integer()) {
    Fail(fmt::format("expected an integer, got {}", value_->dump()));
  }
  const auto x = value_->get<long long>();
  if (x < INT32_MIN || x > INT32_MAX) Fail(fmt::format("integer {} out of range", x));
  return static_cast<int>(x);
}

std::string JsonNode::String() const {
  if (!value_->is_string()) Fail(fmt::format("expected a string, got {}", TypeName(*value_)));
  return value_->get<std::string>();
}

bool JsonNode::Bool() const {
  if (!value_->is_boolean()) Fail(fmt::format("expected true or false, got {}", value_->dump()));
  return value_->get<bool>();
}

Eigen::Vector3d JsonNode::Vector3() const {
  if (!value_->is_array() || value_->size() != 3) {
    Fail(fmt::format("expected 3 numbers [x, y, z], got {}", value_->dump()));
  }
  return {Item(0).Number(), Item(1).Number(), Item(2).Number()};
}

JsonDocument ReadJsonDocument(const std::filesystem::path& path) {
  JsonDocument doc;
  doc.source = path.string();
  doc.value = ParseJson(ReadFile(path), doc.source);
  return doc;
}

void CheckFormat(const JsonNode& doc, const std::string& format, int version) {
  const std::string got = doc.String("format");
  if (got != format) {
    doc.FailAt("format", fmt::format("expected \"{}\", got \"{}\"", format, got));
  }
  const int v = doc.Integer("version");
  if (v != version) {
    doc.FailAt("version", fmt::format("expected {} (this simtree reads version {}), got {}",
                                      version, version, v));
  }
}

}  // namespace simtree
