#include "simtree/report/detail/json_tables.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "simtree/report/detail/html.h"

namespace simtree::report {
namespace {

bool IsPlain(const nlohmann::ordered_json& v) { return !v.is_object() && !v.is_array(); }

bool IsPlainArray(const nlohmann::ordered_json& v) {
  if (!v.is_array()) return false;
  for (const auto& e : v) {
    if (!IsPlain(e)) return false;
  }
  return true;
}

bool IsArrayOfObjects(const nlohmann::ordered_json& v) {
  if (!v.is_array() || v.empty()) return false;
  for (const auto& e : v) {
    if (!e.is_object()) return false;
  }
  return true;
}

std::string Heading(const std::string& path, int depth) {
  const int level = std::min(3 + depth, 6);
  return fmt::format("<h{0} class=\"json-path\">{1}</h{0}>\n", level, EscapeHtml(path));
}

std::string ArrayOfObjectsTable(const nlohmann::ordered_json& rows,
                                const JsonTableOptions& options) {
  std::vector<std::string> columns;
  for (const auto& row : rows) {
    for (const auto& [key, value] : row.items()) {
      if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
    }
  }
  HtmlTable table(columns, "json");
  int shown = 0;
  for (const auto& row : rows) {
    if (shown++ >= options.max_rows) break;
    std::vector<std::string> cells;
    for (const std::string& c : columns) {
      cells.push_back(row.contains(c) ? JsonValueText(row[c], options.max_cell_chars) : "");
    }
    table.AddRow(cells);
  }
  std::string out = table.Html();
  if (static_cast<int>(rows.size()) > options.max_rows) {
    out += NoteHtml(fmt::format("{} more rows not shown", rows.size() - options.max_rows));
  }
  return out;
}

std::string Tables(const nlohmann::ordered_json& value, const std::string& path, int depth,
                   const JsonTableOptions& options) {
  if (IsArrayOfObjects(value)) return ArrayOfObjectsTable(value, options);
  if (!value.is_object() || depth >= options.max_depth) {
    return "<p class=\"json-value\">" + EscapeHtml(JsonValueText(value, options.max_cell_chars)) +
           "</p>\n";
  }
  std::string out;
  HtmlTable plain({"name", "value"}, "json");
  for (const auto& [key, member] : value.items()) {
    if (IsPlain(member) || IsPlainArray(member)) {
      plain.AddRow({key, JsonValueText(member, options.max_cell_chars)});
    }
  }
  if (plain.rows() > 0) out += plain.Html();
  for (const auto& [key, member] : value.items()) {
    if (IsPlain(member) || IsPlainArray(member)) continue;
    const std::string child = path.empty() ? key : path + "." + key;
    out += Heading(child, depth);
    out += Tables(member, child, depth + 1, options);
  }
  return out;
}

}  // namespace

std::string JsonValueText(const nlohmann::ordered_json& value, int max_chars) {
  if (value.is_null()) return "\xE2\x80\x93";
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
  if (value.is_number_float()) {
    const double v = value.get<double>();
    if (!std::isfinite(v)) return "\xE2\x80\x93";
    if (v == std::round(v) && std::abs(v) < 1e15) return fmt::format("{:.0f}", v);
    const double a = std::abs(v);
    if (a >= 100) return fmt::format("{:.1f}", v);
    if (a >= 1) return fmt::format("{:.3f}", v);
    return fmt::format("{:.4g}", v);
  }
  if (IsPlainArray(value)) {
    std::string out = "[";
    for (size_t i = 0; i < value.size(); ++i) {
      out += (i ? ", " : "") + JsonValueText(value[i], max_chars);
      if (static_cast<int>(out.size()) > max_chars)
        return out.substr(0, max_chars) + "\xE2\x80\xA6]";
    }
    return out + "]";
  }
  std::string text = value.dump();
  if (static_cast<int>(text.size()) > max_chars) text = text.substr(0, max_chars) + "\xE2\x80\xA6";
  return text;
}

std::string JsonToHtmlTables(const nlohmann::ordered_json& value, const std::string& path,
                             const JsonTableOptions& options) {
  return Tables(value, path, 0, options);
}

}  // namespace simtree::report
