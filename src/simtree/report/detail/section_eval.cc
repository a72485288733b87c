// The scores against the truth (eval/eval.json, written by `simtree eval`), shown generically:
// every member as tables (json_tables.h), whatever the file's layout.

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/json_tables.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {

Section BuildEvalSection(PageContext& page) {
  Section s{"eval", "Scores against the truth", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFile("eval/eval.json")) {
    s.Missing(
        "eval/eval.json is not in the result: `simtree eval RESULT --gt CAPTURE` scores a "
        "run against a synthetic capture's truth.");
    return s;
  }
  try {
    // Ordered: the tables follow the file's order of members.
    const nlohmann::ordered_json doc =
        nlohmann::ordered_json::parse(ReadFile(folder.Path("eval/eval.json")));
    s.present = true;
    s.html += JsonToHtmlTables(doc);
  } catch (const Error& e) {
    s.LeftOut(std::string("eval/eval.json could not be read: ") + e.what());
  } catch (const nlohmann::json::exception& e) {
    s.LeftOut(std::string("eval/eval.json could not be read: ") + e.what());
  }
  return s;
}

}  // namespace simtree::report
