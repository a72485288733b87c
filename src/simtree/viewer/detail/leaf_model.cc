#include "simtree/viewer/detail/leaf_model.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/viewer/detail/text_lines.h"

namespace simtree::viewer {
namespace {

// The demo is Y-up with the leaf along x and its width along z: (x, y, z)_demo -> (x, -z, y) puts
// the width along y and the upper side's normal along +z, as the tree files are converted.
Eigen::Vector3f FromDemo(double x, double y, double z, double scale) {
  return Eigen::Vector3f(static_cast<float>(x * scale), static_cast<float>(-z * scale),
                         static_cast<float>(y * scale));
}

// "Key=value" of the header line.
int HeaderCount(const TextLine& line, size_t index, const std::string& key,
                const std::string& source) {
  const std::string prefix = key + "=";
  if (index >= line.words.size() || line.words[index].rfind(prefix, 0) != 0) {
    throw InputError(source, "line 1",
                     fmt::format("expected \"{}N\" as word {} of the header "
                                 "\"PetioleVerNum=P LeafVerNum=L LeafFacesNum=F Scale=S\"",
                                 prefix, index + 1));
  }
  const int n = ParseIntegerWord(line.words[index].substr(prefix.size()), source, 1, key);
  if (n < 0) throw InputError(source, "line 1", fmt::format("{}: expected >= 0, got {}", key, n));
  return n;
}

}  // namespace

float LeafModel::Length() const {
  float length = 0.0f;
  const Eigen::Vector3f base = petiole_points.empty() ? Eigen::Vector3f::Zero() : petiole_points[0];
  for (const Eigen::Vector3f& v : vertices) length = std::max(length, (v - base).norm());
  return length;
}

LeafModel ParseLeafModel(const std::string& text, const std::string& source) {
  const std::vector<TextLine> lines = SplitTextLines(text, false);
  if (lines.empty() || lines[0].number != 1) {
    throw InputError(source, "line 1",
                     "expected the header \"PetioleVerNum=P LeafVerNum=L LeafFacesNum=F Scale=S\"");
  }
  const TextLine& header = lines[0];
  const int petioles = HeaderCount(header, 0, "PetioleVerNum", source);
  const int vertices = HeaderCount(header, 1, "LeafVerNum", source);
  const int faces = HeaderCount(header, 2, "LeafFacesNum", source);
  if (header.words.size() != 4 || header.words[3].rfind("Scale=", 0) != 0) {
    throw InputError(source, "line 1", "expected \"Scale=S\" as the header's fourth and last word");
  }
  const double scale = ParseNumberWord(header.words[3].substr(6), source, 1, "Scale");
  if (scale <= 0.0) {
    throw InputError(source, "line 1", fmt::format("Scale: expected > 0, got {}", scale));
  }
  if (vertices < 3 || faces < 1) {
    throw InputError(
        source, "line 1",
        fmt::format("expected a blade of at least 3 vertices and 1 face, got {} and {}", vertices,
                    faces));
  }
  const size_t expected = 1 + static_cast<size_t>(petioles) + vertices + faces;
  if (lines.size() != expected) {
    const int last = lines.back().number;
    throw InputError(source, fmt::format("line {}", last),
                     fmt::format("expected {} lines after the header ({} petiole, {} vertex, {} "
                                 "face lines), got {}",
                                 expected - 1, petioles, vertices, faces, lines.size() - 1));
  }

  LeafModel model;
  model.scale = static_cast<float>(scale);
  size_t next = 1;
  auto row = [&](size_t words, int index, const char* what) -> const TextLine& {
    const TextLine& line = lines[next++];
    if (line.words.size() != words) {
      throw InputError(
          source, fmt::format("line {}", line.number),
          fmt::format("expected {} numbers for a {} line, got {}", words, what, line.words.size()));
    }
    const int i = ParseIntegerWord(line.words[0], source, line.number, "the index");
    if (i != index) {
      throw InputError(source, fmt::format("line {}", line.number),
                       fmt::format("expected {} index {}, got {}", what, index, i));
    }
    return line;
  };
  auto number = [&](const TextLine& line, size_t word, const char* what) {
    return ParseNumberWord(line.words[word], source, line.number, what);
  };
  for (int i = 0; i < petioles; ++i) {
    const TextLine& line = row(5, i, "petiole");
    model.petiole_points.push_back(
        FromDemo(number(line, 1, "x"), number(line, 2, "y"), number(line, 3, "z"), scale));
    const double r = number(line, 4, "radius");
    if (r < 0.0) {
      throw InputError(source, fmt::format("line {}", line.number),
                       fmt::format("expected a radius >= 0, got {}", r));
    }
    model.petiole_radii.push_back(static_cast<float>(r * scale));
  }
  for (int i = 0; i < vertices; ++i) {
    const TextLine& line = row(6, i, "leaf vertex");
    model.vertices.push_back(
        FromDemo(number(line, 1, "x"), number(line, 2, "y"), number(line, 3, "z"), scale));
    model.uvs.emplace_back(static_cast<float>(number(line, 4, "u")),
                           static_cast<float>(number(line, 5, "v")));
  }
  for (int i = 0; i < faces; ++i) {
    const TextLine& line = row(4, i, "face");
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      t[k] = ParseIntegerWord(line.words[1 + k], source, line.number, "a vertex index");
      if (t[k] < 0 || t[k] >= vertices) {
        throw InputError(
            source, fmt::format("line {}", line.number),
            fmt::format("expected vertex indices in [0, {}], got {}", vertices - 1, t[k]));
      }
    }
    // The demo's winding is clockwise seen from the upper side; keep ours counter-clockwise.
    model.triangles.emplace_back(t[0], t[2], t[1]);
  }
  return model;
}

LeafModel ReadLeafModel(const std::filesystem::path& path) {
  return ParseLeafModel(ReadFile(path), path.string());
}

LeafAssets LoadLeafAssets(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw InputError(folder.string(), "", "expected a leaf model folder (leaf.txt and textures)");
  }
  LeafAssets assets;
  assets.name = folder.filename().string();
  if (assets.name.empty()) assets.name = folder.parent_path().filename().string();
  const std::filesystem::path leaf = folder / "leaf.txt";
  if (!std::filesystem::exists(leaf)) {
    throw InputError(leaf.string(), "", "missing: expected the leaf model of the folder");
  }
  assets.model = ReadLeafModel(leaf);
  assets.top = ReadColorImage(folder / "leafup.bmp");
  assets.bottom = ReadColorImage(folder / "leafdown.bmp");
  assets.petiole = ReadColorImage(folder / "petiole.bmp");
  assets.bark = ReadColorImage(folder / "branch.bmp");
  return assets;
}

}  // namespace simtree::viewer
