#pragma once
// The whole page from its sections: head and style, a header with the status line, a summary of
// what is missing and links to the sections, the sections, the data block, the libraries and the
// page's script, in that order (the scripts run once the document is parsed).

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/report/detail/javascript_libraries.h"
#include "simtree/report/detail/page_context.h"

namespace simtree::report {

struct PageParts {
  std::string title;
  std::string subtitle;           // one line under the title
  std::vector<Section> sections;  // in page order
  nlohmann::json data = nlohmann::json::object();
  const JavaScriptLibraries* libraries = nullptr;  // null or incomplete: no scripts
  std::string footer;
};

std::string AssemblePage(const PageParts& parts);

}  // namespace simtree::report
