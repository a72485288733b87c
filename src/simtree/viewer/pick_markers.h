#pragma once
// `simtree track --pick`: the pull stream's first frame in a window (GLFW, OpenGL 3.3 core,
// Dear ImGui), where a person clicks each marker of markers.json in turn; the clicks become the
// tracker's init. Tape markers are a few pixels wide, so the image zooms (wheel, + and -) and
// pans (right- or middle-drag, arrow keys), drawn with its pixels square.
//
//  - Left click: the asked marker is at this pixel; the next marker is asked for.
//  - Backspace: undo the last click or skip.  S: skip the asked marker (not visible).
//  - Enter: finish (once every marker is clicked or skipped).  Escape or closing: cancel.
//  - Scripted input (detail/pick_script.h) drives the same handlers, for tests.
//
//   const MarkerPickResult r = PickMarkers("capture/pull", MarkerPickOptions{});
//   WriteTrackInitJson(r.init, "out/init.json");

#include <filesystem>
#include <string>
#include <vector>

#include "simtree/io/track_init.h"
#include "simtree/viewer/detail/pick_script.h"

namespace simtree::viewer {

struct MarkerPickOptions {
  // The window's largest size (pixels); the frame is fitted into it.
  int max_width = 1280;
  int max_height = 800;
  std::vector<detail::PickAction> script;  // scripted input, one action a frame
  std::string script_source;               // the script's file, for messages
  // Throws OptionError naming the field.
  void Validate() const;
};

struct MarkerPickResult {
  TrackInit init;            // the clicked markers, at the stream's first frame
  std::vector<int> skipped;  // markers of markers.json skipped
  int frames = 0;            // frames drawn
};

// Opens the first frame of `pull_dir` (frames.csv, markers.json required) and lets the user
// click the markers. Throws InputError for a pull folder without markers.json or frames, Error
// when there is no display or no OpenGL 3.3 ("run under xvfb-run, or give --init"), and
// InputError when the user cancels or clicks no marker (nothing is written then).
MarkerPickResult PickMarkers(const std::filesystem::path& pull_dir,
                             const MarkerPickOptions& options);

}  // namespace simtree::viewer
