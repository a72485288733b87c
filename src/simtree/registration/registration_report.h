#pragma once
// What `simtree register` writes: the poses (JSON), the per-pair table (markdown and JSON), the
// before/after picture and the pull camera's pose. Formats in docs/registration.md ("Outputs").

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/io/image_io.h"
#include "simtree/registration/register.h"
#include "simtree/registration/register_extra_view.h"

namespace simtree::registration {

inline constexpr const char* kRegistrationFormat = "simtree.registration";
inline constexpr int kRegistrationFormatVersion = 1;
inline constexpr const char* kPullCameraFormat = "simtree.pull_camera";
inline constexpr int kPullCameraFormatVersion = 1;

// poses.json: the registration frame, the anchor, and per view whether it registered, why not,
// and its frame_from_camera (16 numbers, row-major; null when not registered).
nlohmann::ordered_json PosesToJson(const MultiViewResult& result);

// pairs.json: one object per pair with the paper's columns (time, RMSE, match rate), the
// coarse and fine results, the checks and whether the pose graph kept it.
nlohmann::ordered_json PairsToJson(const MultiViewResult& result);
// pairs.md: the same as a markdown table, failed pairs with their reason.
std::string PairsMarkdown(const MultiViewResult& result);

// pull_camera.json: the pull camera placed in the registration frame (RegisterExtraView): its
// outcome, frame_from_camera (null when not placed), the quality figures and every pair.
nlohmann::ordered_json ExtraViewToJson(const ExtraViewResult& extra);
// The frame_from_camera of a pull_camera.json; nullopt when the camera was not placed. Throws
// InputError naming the file and field.
std::optional<Eigen::Isometry3d> ReadPullCameraJson(const std::filesystem::path& path);

// Before (every view's camera frame taken as the anchor's: where the views start) and after
// (registered), side and top views, one colour per view; views left out are named in the title.
RgbImage BeforeAfterPicture(const std::vector<RegistrationView>& views,
                            const MultiViewResult& result);

}  // namespace simtree::registration
