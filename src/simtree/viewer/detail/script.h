#pragma once
// Scripted input for the viewer (`simtree view --script actions.txt`): what a user does with mouse
// and keys, one action per line, so tests and demos drive the real window. '#' starts a comment.
//
//   pick X Y              press the left button at window pixel (X, Y): grabs the branch there
//   pick-branch B[@S]     press on branch B's point S metres from its base (its tip without @S)
//   drag X Y [FRAMES]     move, button held, to (X, Y) over FRAMES frames (default 1): pulls
//   drag-by DX DY [FRAMES]  the same, by (DX, DY) pixels from where the mouse is
//   release               let go of the button: the rope is released
//   hover X Y             move the mouse there with no button (prints what is under it)
//   wait FRAMES           draw that many frames
//   screenshot PATH       save the window as a PNG
//   key NAME              press a key: space, s, r, l, w, p, q, escape, f12 (see the viewer's help)
//   play | pause | step | reset
//   wind on | off | SPEED (m/s)
//   leaves on | off
//   material branch|level ID frequency|damping|stiffness VALUE
//   orbit DYAW_DEG DPITCH_DEG      zoom FACTOR
//   quit
// A script that does not end with quit leaves the window open for the user.

#include <string>
#include <vector>

#include "simtree/viewer/detail/material_edit.h"

namespace simtree::viewer {

enum class ScriptVerb {
  kPick,
  kPickBranch,
  kDrag,
  kDragBy,
  kRelease,
  kHover,
  kWait,
  kScreenshot,
  kKey,
  kPlay,
  kPause,
  kStep,
  kReset,
  kWind,
  kLeaves,
  kMaterial,
  kOrbit,
  kZoom,
  kQuit
};

struct ScriptAction {
  ScriptVerb verb = ScriptVerb::kWait;
  int line = 0;                 // in the script, for messages
  std::vector<double> numbers;  // pixel coordinates, frame counts, values, in the order written
  std::string text;             // screenshot path, key name
  bool on = false;              // wind on|off (without a SPEED), leaves on|off
  int branch = -1;              // pick-branch, material branch|level ID
  double arc_length = -1.0;     // pick-branch: negative = the tip
  MaterialScope scope = MaterialScope::kBranch;              // material branch|level
  MaterialProperty property = MaterialProperty::kFrequency;  // material's property
};

// Parses a script; `source` names it in errors (InputError with the line and what was expected).
std::vector<ScriptAction> ParseScript(const std::string& text, const std::string& source);
std::vector<ScriptAction> ReadScript(const std::string& path);

}  // namespace simtree::viewer
