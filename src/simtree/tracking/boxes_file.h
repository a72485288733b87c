#pragma once
// boxes.csv (docs/formats.md): what `track` writes beside trajectories.csv and what
// `eval tracking` scores: per frame and marker the box of its whole tape band, its centre, its
// state and a confidence.
//
//   # simtree.track_boxes v1 units=px
//   frame,marker,x,y,w,h,cx,cy,state,confidence
//   0,0,330.61,425.52,7.88,7.06,334.55,429.05,tracked,0.97

#include <filesystem>
#include <string>
#include <vector>

#include "simtree/tracking/track.h"

namespace simtree::tracking {

inline constexpr const char* kBoxesFirstLine = "# simtree.track_boxes v1 units=px";
inline constexpr const char* kBoxesHeader = "frame,marker,x,y,w,h,cx,cy,state,confidence";

std::string BoxesToCsv(const std::vector<FrameBoxes>& frames);
// Parses boxes.csv text (`source` names it in errors, with the line): the first line and header,
// ten fields a row, finite numbers, w and h >= 0, a known state, confidence in [0, 1], frame
// numbers that never decrease, and the same markers in every frame.
std::vector<FrameBoxes> ParseBoxesCsv(const std::string& text, const std::string& source);
std::vector<FrameBoxes> ReadBoxesCsv(const std::filesystem::path& path);
void WriteBoxesCsv(const std::vector<FrameBoxes>& frames, const std::filesystem::path& path);

}  // namespace simtree::tracking
