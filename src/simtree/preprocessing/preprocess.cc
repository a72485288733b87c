#include "simtree/preprocessing/preprocess.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/progress.h"
#include "simtree/io/point_cloud_io.h"

namespace fs = std::filesystem;

namespace simtree::preprocessing {
namespace {

nlohmann::ordered_json Vector(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// One RGB-D image (`load`, named `source` in errors) to a clean tree cloud; an InputError
// (unreadable images, no depth, no tree) becomes the view's failure.
template <class Load>
PreprocessedView PreprocessRgbd(const std::string& name, const std::string& source, Load load,
                                const PreprocessOptions& preprocess,
                                const DepthToCloudOptions& depth) {
  PreprocessedView view;
  view.name = name;
  try {
    const RgbdImage image = load();
    const auto cloud = DepthToCloud(image, depth, source);
    view.result = PreprocessView(cloud, preprocess, source);
  } catch (const InputError& e) {
    view.failure = e.what();
    spdlog::warn("{}", e.what());
  }
  return view;
}

}  // namespace

std::vector<PreprocessedView> PreprocessCaptureViews(const Capture& capture,
                                                     const PreprocessOptions& preprocess,
                                                     const DepthToCloudOptions& depth) {
  preprocess.Validate();
  depth.Validate();
  std::vector<PreprocessedView> views;
  Progress progress("preprocess", static_cast<int64_t>(capture.views.size()), "views");
  for (const ScanView& scan : capture.views) {
    views.push_back(PreprocessRgbd(
        scan.name, scan.directory.string(), [&] { return LoadScanView(scan); }, preprocess, depth));
    progress.Advance();
  }
  return views;
}

PreprocessedView PreprocessPullFrame(const Capture& capture, size_t index,
                                     const PreprocessOptions& preprocess,
                                     const DepthToCloudOptions& depth) {
  preprocess.Validate();
  depth.Validate();
  if (!capture.pull) {
    throw InputError(capture.root.string(), "pull/", "expected a pull-test stream, found none");
  }
  const PullStream& pull = *capture.pull;
  if (index >= pull.frames.size()) {
    throw InputError(
        (pull.directory / "frames.csv").string(), "",
        fmt::format("expected a frame {}, the stream has {}", index, pull.frames.size()));
  }
  return PreprocessRgbd(
      fmt::format("pull_{}", pull.frames[index].frame),
      (pull.directory / pull.frames[index].depth).string(),
      [&] { return LoadPullFrame(pull, index); }, preprocess, depth);
}

std::vector<PreprocessedView> PreprocessCloudFiles(const std::vector<fs::path>& files,
                                                   const Eigen::Vector3d& up,
                                                   const PreprocessOptions& preprocess) {
  preprocess.Validate();
  std::vector<PreprocessedView> views;
  for (const fs::path& file : files) {
    PreprocessedView view;
    view.name = file.stem().string();
    try {
      view.result = PreprocessView(ReadPointCloud(file), preprocess, file.string());
      if (!view.result->ground) view.result->up = up.normalized();
    } catch (const InputError& e) {
      view.failure = e.what();
      spdlog::warn("{}", e.what());
    }
    views.push_back(std::move(view));
  }
  return views;
}

std::vector<PreprocessedView> LoadViews(const fs::path& input, const PreprocessOptions& preprocess,
                                        const DepthToCloudOptions& depth,
                                        const Eigen::Vector3d& cloud_up) {
  preprocess.Validate();
  depth.Validate();
  if (!fs::is_directory(input)) {
    throw InputError(input.string(), "",
                     "expected a folder: a capture (scans/), the output of `simtree preprocess` "
                     "(preprocess.json) or point-cloud files");
  }
  std::vector<PreprocessedView> views;
  if (fs::exists(input / "preprocess.json")) {
    views = ReadPreprocessedViews(input);
  } else if (fs::exists(input / "capture.json") || fs::is_directory(input / "scans")) {
    views = PreprocessCaptureViews(OpenCapture(input), preprocess, depth);
  } else {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(input)) {
      if (entry.is_regular_file() && IsPointCloudFile(entry.path())) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    views = PreprocessCloudFiles(files, cloud_up, preprocess);
  }
  if (views.empty()) {
    throw InputError(input.string(), "",
                     "expected views: scans/view_XX of a capture, preprocess.json, or point-cloud "
                     "files; found none");
  }
  return views;
}

nlohmann::ordered_json PreprocessedViewsToJson(const std::vector<PreprocessedView>& views) {
  nlohmann::ordered_json doc;
  doc["format"] = kPreprocessFormat;
  doc["version"] = kPreprocessFormatVersion;
  doc["frame"] = "each view in its own camera frame (OpenCV: x right, y down, z forward), metres";
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const PreprocessedView& view : views) {
    nlohmann::ordered_json v;
    v["name"] = view.name;
    if (!view.result) {
      v["cloud"] = nullptr;
      v["failure"] = view.failure;
      list.push_back(v);
      continue;
    }
    const PreprocessResult& r = *view.result;
    v["cloud"] = view.name + ".ply";
    v["up"] = Vector(r.up);
    if (r.ground) {
      v["ground"] = {{"normal", Vector(r.ground->normal)},
                     {"offset", r.ground->offset},
                     {"noise_m", r.ground->noise_m},
                     {"points", r.ground->points}};
    } else {
      v["ground"] = nullptr;
    }
    v["point_spacing_m"] = r.point_spacing_m;
    v["voxel_size_m"] = r.voxel_size_m;
    v["input_points"] = r.input_points;
    v["ground_points"] = r.ground_points;
    v["outlier_points"] = r.outlier_points;
    v["downsampled_points"] = r.downsampled_points;
    v["off_tree_points"] = r.off_tree_points;
    v["tree_points"] = r.cloud.points_.size();
    v["downsample_removed_share"] = r.DownsampleRemovedShare();
    v["seconds"] = r.seconds;
    list.push_back(v);
  }
  doc["views"] = list;
  return doc;
}

void WritePreprocessedViews(const std::vector<PreprocessedView>& views, const fs::path& folder) {
  for (const PreprocessedView& view : views) {
    if (view.result) WritePointCloud(view.result->cloud, folder / (view.name + ".ply"));
  }
  WriteFileAtomically(folder / "preprocess.json", PreprocessedViewsToJson(views).dump(1) + "\n");
}

std::vector<PreprocessedView> ReadPreprocessedViews(const fs::path& folder) {
  const JsonDocument file = ReadJsonDocument(folder / "preprocess.json");
  const JsonNode doc = file.root();
  CheckFormat(doc, kPreprocessFormat, kPreprocessFormatVersion);
  std::vector<PreprocessedView> views;
  for (const JsonNode& v : doc.Field("views").Items()) {
    PreprocessedView view;
    view.name = v.String("name");
    const JsonNode cloud = v.Field("cloud");
    if (cloud.is_null()) {
      const auto failure = v.Find("failure");
      view.failure = failure ? failure->String() : std::string("failed in preprocessing");
      views.push_back(std::move(view));
      continue;
    }
    PreprocessResult r;
    r.cloud = ReadPointCloud(folder / cloud.String());
    r.up = v.Vector3("up").normalized();
    const JsonNode ground = v.Field("ground");
    if (!ground.is_null()) {
      GroundPlane g;
      g.normal = ground.Vector3("normal").normalized();
      g.offset = ground.Number("offset");
      g.noise_m = ground.Number("noise_m");
      r.ground = g;
    }
    r.point_spacing_m = v.Number("point_spacing_m");
    r.voxel_size_m = v.Number("voxel_size_m");
    view.result = std::move(r);
    views.push_back(std::move(view));
  }
  return views;
}

}  // namespace simtree::preprocessing
