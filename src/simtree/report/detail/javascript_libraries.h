#pragma once
// The JavaScript libraries the page inlines, read from the Debian packages' files at run time:
//
//   three.js r111          <dir>/three/three.min.js                        libjs-three
//   OrbitControls (r111)   <dir>/three/examples/js/controls/OrbitControls.js  libjs-three
//   Chart.js 3             <dir>/chart.js/chart.min.js                     libjs-chart.js
//
// <dir> is /usr/share/javascript unless the options name another folder (a copy of the same
// files, e.g. from npm, laid out the same way).

#include <filesystem>
#include <string>
#include <vector>

namespace simtree::report {

struct JavaScriptLibrary {
  std::string name;     // "three.js"
  std::string package;  // "libjs-three"
  std::filesystem::path path;
  std::string text;  // the file, escaped for a <script> element
};

struct JavaScriptLibraries {
  std::vector<JavaScriptLibrary> libraries;  // in the order the page needs them
  // Empty when all were found; otherwise one line per missing file, naming its package.
  std::string missing;

  bool complete() const { return missing.empty(); }
  long long bytes() const;
};

// Reads every library found under `dir`; never throws for a missing one (see `missing`).
JavaScriptLibraries LoadJavaScriptLibraries(const std::filesystem::path& dir);

}  // namespace simtree::report
