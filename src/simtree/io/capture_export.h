#pragma once
// A capture folder back to Azure Kinect recordings (`simtree capture-export`): one .mkv per scan
// view (one capture) and pull.mkv (every pull frame at its time), in the layout k4arecorder
// writes, so recordings made from synthetic captures exercise the same path as a user's.
//
// The capture's colour camera must have a colour mode's shape (16:9 or 4:3; synth
// --color-size 1280x720). The calibration written describes that camera without distortion and
// a virtual WFOV unbinned depth camera (1024x1024) at the same place, looking the same way, with
// the colour camera's focal length times 1024 / its width; the depth is resampled into it
// (nearest pixel: no parallax between the two, so no splatting).

#include <filesystem>
#include <string>
#include <vector>

#include "simtree/io/azure_kinect.h"
#include "simtree/io/capture.h"

namespace simtree {

struct CaptureExportOptions {
  AzureColorFormat color_format = AzureColorFormat::kMjpeg;
  bool pull_only = false;  // skip the scan views (synth's are registered to the depth camera)
  void Validate() const {}
};

struct CaptureExportResult {
  std::vector<std::filesystem::path> scans;  // view_00.mkv, ...
  std::filesystem::path pull;                // empty without a pull stream
  int pull_frames = 0;
};

// The calibration.json text for a pinhole colour camera (see above); `source` names the camera
// in the error when it has no colour mode's shape.
std::string PinholeAzureCalibrationJson(const CameraIntrinsics& color,
                                        const std::string& source = "capture intrinsics");

// Writes the recordings into `out_dir` (a staging folder: the caller commits it).
CaptureExportResult ExportCapture(const Capture& capture, const std::filesystem::path& out_dir,
                                  const CaptureExportOptions& options = {});

}  // namespace simtree
