#include "simtree/io/intrinsics_file.h"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"

namespace simtree {

namespace fs = std::filesystem;

namespace {

CameraIntrinsics FromOpen3d(const JsonNode& doc) {
  CameraIntrinsics k;
  k.width = doc.Integer("width");
  k.height = doc.Integer("height");
  const JsonNode m = doc.Field("intrinsic_matrix");
  m.ExpectArray();
  if (m.size() != 9) m.Fail(fmt::format("expected 9 numbers (a 3x3 matrix), got {}", m.size()));
  double v[9];
  for (size_t i = 0; i < 9; ++i) v[i] = m.Item(i).Number();
  // Column-major: [fx, 0, 0, 0, fy, 0, cx, cy, 1]. A row-major matrix puts cx at [2].
  if (v[2] != 0 || v[5] != 0 || v[8] != 1 || v[1] != 0) {
    m.Fail(fmt::format(
        "expected [fx, 0, 0, 0, fy, 0, cx, cy, 1] (column-major, as Open3D writes it), got [{}]",
        fmt::join(v, ", ")));
  }
  k.fx = v[0];
  k.fy = v[4];
  k.cx = v[6];
  k.cy = v[7];
  ValidateIntrinsics(k, doc.source());
  return k;
}

}  // namespace

CameraIntrinsics ReadOpen3dIntrinsicJson(const fs::path& path) {
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  doc.ExpectObject();
  return FromOpen3d(doc);
}

CameraIntrinsics ReadIntrinsicsFile(const fs::path& path) {
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  doc.ExpectObject();
  if (doc.Has("intrinsic_matrix")) return FromOpen3d(doc);
  if (doc.Has("fx")) return ReadIntrinsicsJson(path);
  doc.Fail(
      "expected a camera: simtree's intrinsics.json (width, height, fx, fy, cx, cy, "
      "depth_scale_m) or Open3D's PinholeCameraIntrinsic JSON (width, height, "
      "intrinsic_matrix)");
}

}  // namespace simtree
