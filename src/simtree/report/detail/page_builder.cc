#include "simtree/report/detail/page_builder.h"

#include <fmt/format.h>

#include "simtree/report/detail/html.h"
#include "simtree/report/detail/page_assets.h"

namespace simtree::report {
namespace {

std::string Header(const PageParts& parts) {
  std::string out = "<header>\n<h1>" + EscapeHtml(parts.title) + "</h1>\n";
  out +=
      "<div id=\"report-status\" class=\"status\" data-state=\"no-script\">JavaScript has not "
      "run: the charts and the 3D view need it.</div>\n";
  out += "<p class=\"generated\">" + EscapeHtml(parts.subtitle) + "</p>\n<nav>";
  for (const Section& s : parts.sections) {
    out += fmt::format("<a href=\"#{}\">{}</a>", s.id, EscapeHtml(s.title));
  }
  return out + "</nav>\n</header>\n";
}

std::string MissingSummary(const PageParts& parts) {
  std::string items;
  int count = 0;
  for (const Section& s : parts.sections) {
    for (const std::string& n : s.notes) {
      items += fmt::format("<li><a href=\"#{}\">{}</a>: {}</li>\n", s.id, EscapeHtml(s.title),
                           EscapeHtml(n));
      ++count;
    }
  }
  if (count == 0) return "";
  return fmt::format(
      "<section id=\"missing\"><h2>Missing or left out ({})</h2>\n"
      "<ul class=\"summary-notes\">\n{}</ul></section>\n",
      count, items);
}

}  // namespace

std::string AssemblePage(const PageParts& parts) {
  std::string page = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<title>" + EscapeHtml(parts.title) + "</title>\n<style>" + std::string(PageStyle()) +
          "</style>\n</head>\n<body>\n";
  page += Header(parts) + "<main>\n";
  page += MissingSummary(parts);
  for (const Section& s : parts.sections) {
    page += fmt::format("<section id=\"{}\" data-present=\"{}\">\n<h2>{}</h2>\n", s.id,
                        s.present ? "yes" : "no", EscapeHtml(s.title));
    page += s.html + "</section>\n";
  }
  page += "</main>\n<footer>" + EscapeHtml(parts.footer) + "</footer>\n";
  page += "<script type=\"application/json\" id=\"simtree-data\">" +
          EscapeJsonForScript(parts.data.dump()) + "</script>\n";
  if (parts.libraries && parts.libraries->complete()) {
    for (const JavaScriptLibrary& l : parts.libraries->libraries) {
      page += fmt::format("<script data-library=\"{}\" data-package=\"{}\">\n", l.name, l.package);
      page += l.text + "\n</script>\n";
    }
  }
  page += "<script>" + std::string(PageScript()) + "</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace simtree::report
