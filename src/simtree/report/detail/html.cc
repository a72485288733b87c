#include "simtree/report/detail/html.h"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

namespace simtree::report {

std::string EscapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string EscapeScriptText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  const auto starts_with = [&](size_t i, std::string_view what) {
    if (i + what.size() > text.size()) return false;
    for (size_t k = 0; k < what.size(); ++k) {
      if (std::tolower(static_cast<unsigned char>(text[i + k])) != what[k]) return false;
    }
    return true;
  };
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] != '<') continue;
    if (starts_with(i, "</script")) out += '\\';
    if (starts_with(i, "<!--")) out += '\\';
  }
  return out;
}

std::string EscapeJsonForScript(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (const char c : json) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

std::string FormatNumber(double value, int digits) {
  if (!std::isfinite(value)) return "\xE2\x80\x93";  // en dash
  return fmt::format("{:.{}f}", value, digits);
}

std::string FormatBytes(long long bytes) {
  if (bytes >= 1'000'000) return fmt::format("{:.1f} MB", bytes / 1e6);
  if (bytes >= 1'000) return fmt::format("{:.0f} kB", bytes / 1e3);
  return fmt::format("{} B", bytes);
}

std::string NoteHtml(std::string_view text) {
  return "<p class=\"note\">" + EscapeHtml(text) + "</p>\n";
}

std::string MissingHtml(std::string_view text) {
  return "<p class=\"missing\">" + EscapeHtml(text) + "</p>\n";
}

HtmlTable::HtmlTable(std::vector<std::string> header, std::string css_class)
    : header_(std::move(header)), css_class_(std::move(css_class)) {}

void HtmlTable::AddRow(const std::vector<std::string>& cells, const std::string& row_class) {
  std::vector<std::string> escaped;
  escaped.reserve(cells.size());
  for (const std::string& c : cells) escaped.push_back(EscapeHtml(c));
  AddHtmlRow(escaped, row_class);
}

void HtmlTable::AddHtmlRow(const std::vector<std::string>& cells_html,
                           const std::string& row_class) {
  body_ += row_class.empty() ? "<tr>" : "<tr class=\"" + EscapeHtml(row_class) + "\">";
  for (const std::string& c : cells_html) body_ += "<td>" + c + "</td>";
  body_ += "</tr>\n";
  ++rows_;
}

std::string HtmlTable::Html() const {
  std::string out = css_class_.empty() ? "<table>\n" : "<table class=\"" + css_class_ + "\">\n";
  out += "<thead><tr>";
  for (const std::string& h : header_) out += "<th>" + EscapeHtml(h) + "</th>";
  out += "</tr></thead>\n<tbody>\n" + body_ + "</tbody></table>\n";
  return out;
}

}  // namespace simtree::report
