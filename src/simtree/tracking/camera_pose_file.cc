#include "simtree/tracking/camera_pose_file.h"

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/io/ground_truth.h"

namespace simtree::tracking {

Eigen::Isometry3d ReadCameraPoseJson(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(path.string(), "", "missing (the pull camera's pose: pull_camera.json)");
  }
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root().ExpectObject();
  if (doc.Has("world_from_camera")) return PoseFromJson(doc.Field("world_from_camera"));
  if (!doc.Has("format")) {
    doc.Fail(
        "expected a pull camera pose: {\"world_from_camera\": [16 numbers]} (synth's "
        "gt/pull_camera.json) or simtree.pull_camera (register's pull_camera.json)");
  }
  CheckFormat(doc, "simtree.pull_camera", 1);
  if (!doc.Bool("placed")) {
    doc.FailAt("placed", "the pull camera was not placed by registration (its status: " +
                             (doc.Has("status") ? doc.String("status") : std::string("none")) +
                             "); give a pose another way or pick the markers (--pick)");
  }
  return PoseFromJson(doc.Field("frame_from_camera"));
}

}  // namespace simtree::tracking
