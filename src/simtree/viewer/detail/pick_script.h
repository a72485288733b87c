#pragma once
// Scripted input for the picking window (`simtree track --pick --pick-script FILE`), so tests
// drive the real window through the same handlers as the mouse and keys. One action per line,
// '#' starts a comment:
//
//   click X Y          left click at window pixel (X, Y)
//   click-image U V    left click where image pixel (U, V) is shown now (mapped through the view)
//   zoom FACTOR [X Y]  zoom by FACTOR about window pixel (X, Y) (default: the window's centre)
//   pan DX DY          move the image by (DX, DY) window pixels
//   key NAME           backspace (undo), s (skip), enter (finish), escape (cancel)
//   wait FRAMES        draw that many frames
//
// The script runs one action a frame; one that does not finish leaves the window to the user.

#include <filesystem>
#include <string>
#include <vector>

namespace simtree::viewer::detail {

enum class PickVerb { kClick, kClickImage, kZoom, kPan, kKey, kWait };

struct PickAction {
  PickVerb verb = PickVerb::kWait;
  int line = 0;
  std::vector<double> numbers;
  std::string key;  // kKey: backspace, s, enter or escape
};

// Throws InputError naming the file and line for an unknown verb, a wrong count of numbers or an
// unknown key.
std::vector<PickAction> ParsePickScript(const std::string& text, const std::string& source);
std::vector<PickAction> ReadPickScript(const std::filesystem::path& path);

}  // namespace simtree::viewer::detail
