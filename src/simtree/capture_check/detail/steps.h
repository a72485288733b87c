#pragma once
// The steps of CheckCapture, each adding its checks to `out`.

#include <string>
#include <vector>

#include "simtree/capture_check/capture_check.h"
#include "simtree/io/capture.h"
#include "simtree/preprocessing/preprocess.h"

namespace simtree::capture_check::detail {

// Depth on the tree, distance, blur and exposure of one frame (a scan view, a pull frame).
void CheckFrame(const std::string& subject, const RgbdImage& image,
                const preprocessing::PreprocessedView& view, const CheckThresholds& t,
                std::vector<Check>* out);

// The number of views, each view's frame and the coverage around the tree.
void CheckScans(const Capture& capture, const CaptureCheckOptions& options,
                std::vector<Check>* out);

// Frames, rate, length and dropped frames of the pull stream; its first frame (init.json's when
// given) with its tape markers.
void CheckPull(const Capture& capture, const CaptureCheckOptions& options, std::vector<Check>* out);

}  // namespace simtree::capture_check::detail
