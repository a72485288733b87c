#include "simtree/io/track_init.h"

#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"

namespace fs = std::filesystem;

namespace simtree {
namespace {

constexpr const char* kTrackInitFormat = "simtree.track_init";
constexpr int kTrackInitVersion = 1;

Eigen::Vector2d ReadPixel(const JsonNode& node) {
  node.ExpectArray();
  if (node.size() != 2) {
    node.Fail(fmt::format("expected 2 numbers [column, row], got {}", node.size()));
  }
  const Eigen::Vector2d pixel(node.Item(0).Number(), node.Item(1).Number());
  if (pixel.x() < -0.5 || pixel.y() < -0.5) {
    node.Fail(fmt::format("expected a pixel inside the image (>= -0.5), got [{}, {}]", pixel.x(),
                          pixel.y()));
  }
  return pixel;
}

double Rounded(double value) { return std::round(value * 1e6) / 1e6; }

}  // namespace

TrackInit ReadTrackInitJson(const fs::path& path) {
  if (!fs::is_regular_file(path)) {
    throw InputError(path.string(), "",
                     "missing (the tracker's start: each marker's first-frame pixel; "
                     "`simtree track --pick` writes one)");
  }
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kTrackInitFormat, kTrackInitVersion);
  TrackInit init;
  const JsonNode frame = doc.Field("frame");
  init.frame = frame.Integer();
  if (init.frame < 0) frame.Fail(fmt::format("expected a frame number >= 0, got {}", init.frame));
  const JsonNode list = doc.Field("markers").ExpectArray();
  if (list.size() == 0) list.Fail("expected at least one marker, got an empty list");
  std::set<int> seen;
  for (const JsonNode& item : list.Items()) {
    MarkerPixel marker;
    const JsonNode id = item.ExpectObject().Field("id");
    marker.id = id.Integer();
    if (marker.id < 0) id.Fail(fmt::format("expected an id >= 0, got {}", marker.id));
    if (!seen.insert(marker.id).second) {
      id.Fail(fmt::format("marker id {} appears twice", marker.id));
    }
    marker.pixel = ReadPixel(item.Field("pixel"));
    init.markers.push_back(marker);
  }
  return init;
}

void WriteTrackInitJson(const TrackInit& init, const fs::path& path) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const MarkerPixel& m : init.markers) {
    list.push_back({{"id", m.id}, {"pixel", {Rounded(m.pixel.x()), Rounded(m.pixel.y())}}});
  }
  const nlohmann::ordered_json doc = {{"format", kTrackInitFormat},
                                      {"version", kTrackInitVersion},
                                      {"frame", init.frame},
                                      {"markers", list}};
  WriteFileAtomically(path, doc.dump(1) + "\n");
}

}  // namespace simtree
