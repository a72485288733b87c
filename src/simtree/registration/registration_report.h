#pragma once
// What `simtree register` writes: the poses (JSON), the per-pair table (markdown and JSON) and
// the before/after picture. Formats in docs/formats.md ("Registration").

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/io/image_io.h"
#include "simtree/registration/register.h"

namespace simtree::registration {

inline constexpr const char* kRegistrationFormat = "simtree.registration";
inline constexpr int kRegistrationFormatVersion = 1;

// poses.json: the registration frame, the anchor, and per view whether it registered, why not,
// and its frame_from_camera (16 numbers, row-major; null when not registered).
nlohmann::ordered_json PosesToJson(const MultiViewResult& result);

// pairs.json: one object per pair with the paper's columns (time, RMSE, match rate), the
// coarse and fine results, the checks and whether the pose graph kept it.
nlohmann::ordered_json PairsToJson(const MultiViewResult& result);
// pairs.md: the same as a markdown table, failed pairs with their reason.
std::string PairsMarkdown(const MultiViewResult& result);

// Before (every view's camera frame taken as the anchor's: where the views start) and after
// (registered), side and top views, one colour per view; views left out are named in the title.
RgbImage BeforeAfterPicture(const std::vector<RegistrationView>& views,
                            const MultiViewResult& result);

}  // namespace simtree::registration
