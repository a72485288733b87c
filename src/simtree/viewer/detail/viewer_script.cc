#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/viewer/detail/viewer_impl.h"

namespace simtree::viewer {

void Viewer::Impl::DoAction(const ScriptAction& a) {
  switch (a.verb) {
    case ScriptVerb::kPick:
      mouse_x = a.numbers[0];
      mouse_y = a.numbers[1];
      Press(a.numbers[0], a.numbers[1]);
      if (drag != Drag::kGrab) {
        spdlog::warn("{}: line {}: pick: no branch at ({}, {})", options.script_source, a.line,
                     a.numbers[0], a.numbers[1]);
      }
      break;
    case ScriptVerb::kPickBranch: {
      if (a.branch >= tree.size()) {
        throw InputError(options.script_source, fmt::format("line {}", a.line),
                         fmt::format("pick-branch: expected a branch id in [0, {}], got {}",
                                     tree.size() - 1, a.branch));
      }
      const double length = tree.branches[a.branch].Length();
      const double s = a.arc_length < 0.0 ? length : std::min(a.arc_length, length);
      const auto pixel = SceneView().Project(sim->PointPosition(a.branch, s));
      if (!pixel) {
        spdlog::warn("{}: line {}: pick-branch: branch {} is behind the camera",
                     options.script_source, a.line, a.branch);
        break;
      }
      mouse_x = pixel->x() + ViewportX();
      mouse_y = pixel->y();
      spdlog::info("view: pick-branch {} at pixel ({:.0f}, {:.0f})", a.branch, mouse_x, mouse_y);
      Press(mouse_x, mouse_y);
      break;
    }
    case ScriptVerb::kDrag:
    case ScriptVerb::kDragBy:
      drag_to_x = a.numbers[0] + (a.verb == ScriptVerb::kDragBy ? mouse_x : 0.0);
      drag_to_y = a.numbers[1] + (a.verb == ScriptVerb::kDragBy ? mouse_y : 0.0);
      drag_frames_left = static_cast<int>(a.numbers[2]);
      break;
    case ScriptVerb::kRelease:
      ReleaseButton();
      break;
    case ScriptVerb::kHover:
      Move(a.numbers[0], a.numbers[1]);
      UpdateHover();
      if (hovered >= 0) {
        spdlog::info("view: hover ({}, {}): {}", a.numbers[0], a.numbers[1],
                     BranchDescription(tree, *sim, hovered));
      } else {
        spdlog::info("view: hover ({}, {}): nothing", a.numbers[0], a.numbers[1]);
      }
      break;
    case ScriptVerb::kWait:
      script_wait = static_cast<int>(a.numbers[0]);
      break;
    case ScriptVerb::kScreenshot:
      pending_screenshots.push_back(a.text);
      break;
    case ScriptVerb::kKey:
      Key(a.text);
      break;
    case ScriptVerb::kPlay:
      playing = true;
      break;
    case ScriptVerb::kPause:
      playing = false;
      break;
    case ScriptVerb::kStep:
      playing = false;
      step_once = true;
      break;
    case ScriptVerb::kReset:
      Reset();
      break;
    case ScriptVerb::kWind:
      if (!a.numbers.empty()) {
        wind_speed = static_cast<float>(a.numbers[0]);
        SetWind(wind_speed > 0.0f);
      } else {
        SetWind(a.on);
      }
      break;
    case ScriptVerb::kLeaves:
      SetLeaves(a.on);
      break;
    case ScriptVerb::kMaterial: {
      const bool level = a.scope == MaterialScope::kLevel;
      if (!level && a.branch >= tree.size()) {
        throw InputError(options.script_source, fmt::format("line {}", a.line),
                         fmt::format("material: expected a branch id in [0, {}], got {}",
                                     tree.size() - 1, a.branch));
      }
      EditMaterial(a.property, a.numbers[0],
                   level ? BranchesOfLevel(tree, a.branch) : std::vector<int>{a.branch});
      break;
    }
    case ScriptVerb::kOrbit:
      orbit.Orbit(DegToRad(a.numbers[0]), DegToRad(a.numbers[1]));
      break;
    case ScriptVerb::kZoom:
      orbit.Zoom(a.numbers[0]);
      break;
    case ScriptVerb::kQuit:
      quit = true;
      break;
  }
}

void Viewer::Impl::RunScript() {
  // A drag in progress moves the mouse a step per frame; a wait holds the script.
  if (drag_frames_left > 0) {
    const double f = 1.0 / drag_frames_left;
    Move(mouse_x + f * (drag_to_x - mouse_x), mouse_y + f * (drag_to_y - mouse_y));
    --drag_frames_left;
    return;
  }
  if (script_wait > 0) {
    --script_wait;
    return;
  }
  // Everything up to the next action that takes frames (or a screenshot, taken this frame).
  while (script_next < options.script.size() && !quit) {
    const ScriptAction& a = options.script[script_next++];
    DoAction(a);
    if (a.verb == ScriptVerb::kWait && script_wait > 0) {
      --script_wait;
      return;
    }
    if (a.verb == ScriptVerb::kDrag || a.verb == ScriptVerb::kDragBy) {
      RunScript();
      return;
    }
    if (a.verb == ScriptVerb::kScreenshot) return;
  }
}

}  // namespace simtree::viewer
