#pragma once
// The views of a capture folder preprocessed one by one, and the folder `simtree preprocess`
// writes (one PLY per view and preprocess.json), which `simtree register` reads as well as a
// capture. A view that cannot be used (unreadable images, size not matching its intrinsics, no
// depth, nothing above the ground) is kept with the reason instead of stopping the others.
//
// Usage:
//   const simtree::Capture capture = simtree::OpenCapture("scene/");
//   const auto views = simtree::preprocessing::PreprocessCaptureViews(capture);
//   simtree::preprocessing::WritePreprocessedViews(views, "clean/");

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/io/capture.h"
#include "simtree/preprocessing/depth_to_cloud.h"
#include "simtree/preprocessing/preprocess_view.h"

namespace simtree::preprocessing {

inline constexpr const char* kPreprocessFormat = "simtree.preprocess";
inline constexpr int kPreprocessFormatVersion = 1;

struct PreprocessedView {
  std::string name;
  std::optional<PreprocessResult> result;  // absent when the view failed
  std::string failure;                     // why it failed
};

// Every scan view of `capture`, in order. Never throws for one bad view.
std::vector<PreprocessedView> PreprocessCaptureViews(const Capture& capture,
                                                     const PreprocessOptions& preprocess = {},
                                                     const DepthToCloudOptions& depth = {});

// Frame `index` of the capture's pull-test stream (its first, still frame by default), through
// the same preprocessing as the scan views; named "pull_<frame>". A frame that cannot be used is
// returned with the reason. Throws InputError when the capture has no pull stream or no such
// frame.
PreprocessedView PreprocessPullFrame(const Capture& capture, size_t index = 0,
                                     const PreprocessOptions& preprocess = {},
                                     const DepthToCloudOptions& depth = {});

// Point-cloud files as views (each in its sensor's frame; `up` in that frame when no ground is
// found), named after the files.
std::vector<PreprocessedView> PreprocessCloudFiles(const std::vector<std::filesystem::path>& files,
                                                   const Eigen::Vector3d& up,
                                                   const PreprocessOptions& preprocess = {});

// The views of `input`, whichever it is: a folder written by `simtree preprocess`
// (preprocess.json, read as it is), a capture folder (scans/, preprocessed now) or a folder of
// point-cloud files (.ply, .pcd, .xyz, .txt, .pts, .las, one view each in name order; `cloud_up` is
// up in their frame when no ground is found). Throws InputError when it is none of these or holds
// no view.
std::vector<PreprocessedView> LoadViews(
    const std::filesystem::path& input, const PreprocessOptions& preprocess = {},
    const DepthToCloudOptions& depth = {},
    const Eigen::Vector3d& cloud_up = -Eigen::Vector3d::UnitY());

// <folder>/<name>.ply for every usable view and <folder>/preprocess.json with every view's
// numbers (or failure). The folder must exist.
void WritePreprocessedViews(const std::vector<PreprocessedView>& views,
                            const std::filesystem::path& folder);
nlohmann::ordered_json PreprocessedViewsToJson(const std::vector<PreprocessedView>& views);
// Reads what WritePreprocessedViews wrote. Throws InputError naming the file and field.
std::vector<PreprocessedView> ReadPreprocessedViews(const std::filesystem::path& folder);

}  // namespace simtree::preprocessing
