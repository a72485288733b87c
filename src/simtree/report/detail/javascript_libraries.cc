#include "simtree/report/detail/javascript_libraries.h"

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/report/detail/html.h"

namespace simtree::report {

long long JavaScriptLibraries::bytes() const {
  long long total = 0;
  for (const JavaScriptLibrary& l : libraries) total += static_cast<long long>(l.text.size());
  return total;
}

JavaScriptLibraries LoadJavaScriptLibraries(const std::filesystem::path& dir) {
  struct Wanted {
    const char* name;
    const char* package;
    const char* relative;
  };
  static constexpr Wanted kWanted[] = {
      {"three.js", "libjs-three", "three/three.min.js"},
      {"OrbitControls", "libjs-three", "three/examples/js/controls/OrbitControls.js"},
      {"Chart.js", "libjs-chart.js", "chart.js/chart.min.js"},
  };
  JavaScriptLibraries out;
  for (const Wanted& w : kWanted) {
    const std::filesystem::path path = dir / w.relative;
    if (!std::filesystem::is_regular_file(path)) {
      out.missing += fmt::format(
          "{} not found at {}: install the Debian package {} "
          "(scripts/install-deps.sh installs it) or point "
          "ReportOptions::javascript_dir (simtree report --javascript-dir) "
          "at a folder laid out like /usr/share/javascript\n",
          w.name, path.string(), w.package);
      continue;
    }
    out.libraries.push_back({w.name, w.package, path, EscapeScriptText(ReadFile(path))});
  }
  return out;
}

}  // namespace simtree::report
