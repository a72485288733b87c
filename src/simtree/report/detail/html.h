#pragma once
// Small pieces of HTML the report's sections are made of: escaping, numbers, notes and tables.
// Everything a section shows from a file goes through EscapeHtml; JSON put inside a <script>
// element goes through EscapeScriptText, so no file's text can end the element early.

#include <string>
#include <string_view>
#include <vector>

namespace simtree::report {

// & < > " ' as entities.
std::string EscapeHtml(std::string_view text);
// JavaScript source made safe inside a <script> element: "</script" (any case) becomes
// "<\/script" and "<!--" becomes "<\!--" (the same code to JavaScript).
std::string EscapeScriptText(std::string_view text);
// JSON text made safe inside a <script type="application/json"> element: every "<" (which JSON
// has only inside strings) becomes the escape \u003c.
std::string EscapeJsonForScript(std::string_view json);

// `value` with `digits` decimals; "–" for NaN or infinity.
std::string FormatNumber(double value, int digits);
// A byte count as "1.2 MB", "340 kB" or "12 B" (decimal units).
std::string FormatBytes(long long bytes);

// <p class="note">text</p>, and the same with class "missing" for what is not in the result.
std::string NoteHtml(std::string_view text);
std::string MissingHtml(std::string_view text);

// A table with a header row. Cells are text (escaped) unless added with AddHtmlRow.
class HtmlTable {
 public:
  explicit HtmlTable(std::vector<std::string> header, std::string css_class = "");
  // `row_class`: a CSS class for the row ("" none).
  void AddRow(const std::vector<std::string>& cells, const std::string& row_class = "");
  void AddHtmlRow(const std::vector<std::string>& cells_html, const std::string& row_class = "");
  int rows() const { return rows_; }
  std::string Html() const;

 private:
  std::vector<std::string> header_;
  std::string css_class_;
  std::string body_;
  int rows_ = 0;
};

}  // namespace simtree::report
