// The static tree: reconstruct's picture (the model over the merged cloud) and its numbers.

#include <filesystem>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/tree_summary.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"
#include "simtree/report/detail/tree_facts.h"

namespace simtree::report {

Section BuildReconstructionSection(PageContext& page) {
  Section s{"reconstruction", "Static tree", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFolder("reconstruct")) {
    s.Missing("reconstruct/ is not in the result: no static tree was reconstructed.");
    return s;
  }
  s.present = true;
  if (folder.HasFile("reconstruct/picture.png")) {
    s.html += page.Figure(folder.Path("reconstruct/picture.png"),
                          "The reconstructed tree over the merged cloud, front and side.", s);
  } else {
    s.Missing("reconstruct/picture.png is missing.");
  }
  if (folder.HasFile("reconstruct/static.json")) {
    try {
      s.html += TreeFactsTable(Summarize(ReadTreeJson(folder.Path("reconstruct/static.json"))));
    } catch (const Error& e) {
      s.LeftOut(std::string("reconstruct/static.json could not be read: ") + e.what());
    }
  } else {
    s.Missing("reconstruct/static.json is missing.");
  }
  if (folder.HasFile("reconstruct/static.ply")) {
    s.Remark(fmt::format("The tube mesh is reconstruct/static.ply ({}), for MeshLab or Blender.",
                         FormatBytes(static_cast<long long>(
                             std::filesystem::file_size(folder.Path("reconstruct/static.ply"))))));
  }
  return s;
}

}  // namespace simtree::report
