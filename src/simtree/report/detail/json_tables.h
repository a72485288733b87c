#pragma once
// Any JSON document as HTML tables, for files whose layout the report does not know in advance
// (eval/eval.json): an object's plain members become a two-column table of name and value, each
// nested object a sub-heading (its path) with its own tables, an array of objects one table with a
// column per member, an array of plain values one cell.

#include <string>

#include <nlohmann/json.hpp>

namespace simtree::report {

struct JsonTableOptions {
  int max_depth = 6;   // deeper objects are shown as compact JSON
  int max_rows = 500;  // rows of one table (the rest counted in a note)
  int max_cell_chars = 160;
};

// A plain value as text: integers as is, other numbers with 3-4 significant decimals, strings
// unquoted, null as "–", arrays and objects as compact JSON (cut at max_cell_chars).
std::string JsonValueText(const nlohmann::ordered_json& value, int max_chars = 160);

// The tables of `value` (members in the file's order); `path` names it in sub-headings ("" for the
// document).
std::string JsonToHtmlTables(const nlohmann::ordered_json& value, const std::string& path = "",
                             const JsonTableOptions& options = {});

}  // namespace simtree::report
