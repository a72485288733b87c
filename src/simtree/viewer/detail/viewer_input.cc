#include <imgui.h>

#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/viewer/detail/picking.h"
#include "simtree/viewer/detail/viewer_impl.h"

namespace simtree::viewer {

std::string BranchDescription(const Tree& tree, const dynamics::TreeDynamics& sim, int id) {
  const Branch& b = tree.branches[id];
  const Material& m = sim.material(id);
  return fmt::format(
      "branch {} (level {}, parent {}): f {:.3g} Hz, damping {:.3g}, k {:.4g} N/m, "
      "{}",
      id, b.level, b.parent, m.modes[0].frequency_hz, m.modes[0].damping_ratio, m.stiffness,
      ToString(m.source));
}

void Viewer::Impl::Key(const std::string& name) {
  if (name == "space") {
    playing = !playing;
  } else if (name == "s") {
    playing = false;
    step_once = true;
  } else if (name == "r") {
    Reset();
  } else if (name == "l") {
    SetLeaves(!style.leaves);
  } else if (name == "w") {
    SetWind(!sim->wind().enabled);
  } else if (name == "g") {
    style.grid = !style.grid;
  } else if (name == "c") {
    style.colouring = static_cast<BranchColouring>((static_cast<int>(style.colouring) + 1) % 3);
  } else if (name == "h") {
    panel = !panel;
  } else if (name == "p" || name == "f12") {
    pending_screenshots.push_back(NextScreenshotPath());
  } else if (name == "q" || name == "escape") {
    quit = true;
  } else {
    spdlog::debug("view: key {} does nothing", name);
  }
}

void Viewer::Impl::Press(double x, double y) {
  mouse_x = x;
  mouse_y = y;
  left_down = true;
  if (x < ViewportX()) return;  // on the panel
  if (shift) {
    drag = Drag::kPan;
    return;
  }
  const CameraView view = SceneView();
  const Ray ray = view.PixelRay(x - ViewportX(), y);
  const auto hit = PickBranch(tree, sim->node_positions(), view, ray);
  if (!hit) {
    drag = Drag::kOrbit;
    return;
  }
  drag = Drag::kGrab;
  selected = hit->branch;
  grab_arc = hit->arc_length;
  grab_plane_point = hit->point;
  grab_plane_normal = view.Forward();
  grab_target = hit->point;
  spdlog::info("view: grabbed {} at {:.3f} m", BranchDescription(tree, *sim, selected), grab_arc);
}

void Viewer::Impl::PullTo(double x, double y) {
  const CameraView view = SceneView();
  const Ray ray = view.PixelRay(x - ViewportX(), y);
  const double denom = ray.direction.dot(grab_plane_normal);
  if (std::abs(denom) < 1e-9) return;
  const double t = (grab_plane_point - ray.origin).dot(grab_plane_normal) / denom;
  if (t <= 0.0) return;
  grab_target = ray.origin + t * ray.direction;
  const Eigen::Vector3d rest = tree.branches[selected].PointAt(grab_arc);
  const Eigen::Vector3d pull_vector = grab_target - rest;
  const double distance = pull_vector.norm();
  // Anchored beyond the cursor, so the rope's direction holds as the point comes near it.
  const Eigen::Vector3d direction =
      distance > 1e-9 ? Eigen::Vector3d(pull_vector / distance) : grab_plane_normal;
  dynamics::Rope rope;
  rope.branch = selected;
  rope.arc_length = grab_arc;
  rope.anchor = grab_target + 2.0 * direction;
  if (grab_mode == GrabMode::kFollow) {
    // The tension that moves the point statically to the cursor: the compliance along the pull
    // from a small probe (the model is linear), capped like the demo's force slider, since a
    // branch cannot stretch along its own axis.
    dynamics::Rope probe = rope;
    probe.mode = dynamics::Rope::Mode::kDisplacement;
    probe.displacement_m = 0.01;
    probe.anchor = sim->PointPosition(selected, grab_arc) + 2.0 * direction;
    double tension = 0.0;
    try {
      const int id = sim->AttachRope(probe);
      tension = sim->RopeTension(id) * distance / probe.displacement_m;
      sim->ReleaseRope(id);
    } catch (const InputError&) {
      tension = max_tension;  // the point cannot move that way: pull as hard as allowed
    }
    rope.force_n = std::min(tension, static_cast<double>(max_tension));
  } else {
    rope.force_n = std::min(force_per_metre * distance, static_cast<double>(max_tension));
  }
  if (grab_rope >= 0 && sim->HasRope(grab_rope)) {
    sim->UpdateRope(grab_rope, rope);
  } else {
    grab_rope = sim->AttachRope(rope);
  }
}

void Viewer::Impl::Move(double x, double y) {
  const double dx = x - mouse_x, dy = y - mouse_y;
  mouse_x = x;
  mouse_y = y;
  if (!left_down) return;
  switch (drag) {
    case Drag::kOrbit:
      orbit.Orbit(-0.006 * dx, 0.006 * dy);
      break;
    case Drag::kPan:
      orbit.Pan(dx, dy, SceneView().height);
      break;
    case Drag::kGrab:
      PullTo(x, y);
      break;
    case Drag::kNone:
      break;
  }
}

void Viewer::Impl::ReleaseButton() {
  left_down = false;
  if (drag == Drag::kGrab && grab_rope >= 0) {
    if (sim->HasRope(grab_rope)) {
      spdlog::info("view: released branch {} (tension was {:.1f} N)", selected,
                   sim->RopeTension(grab_rope));
      sim->ReleaseRope(grab_rope);
    }
    grab_rope = -1;
  }
  drag = Drag::kNone;
}

void Viewer::Impl::UpdateHover() {
  hovered = -1;
  if (mouse_x < ViewportX()) return;
  const CameraView view = SceneView();
  if (mouse_x - ViewportX() >= view.width || mouse_y < 0 || mouse_y >= view.height) return;
  const auto hit =
      PickBranch(tree, sim->node_positions(), view, view.PixelRay(mouse_x - ViewportX(), mouse_y));
  if (hit) hovered = hit->branch;
}

void Viewer::Impl::HandleRealInput() {
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  int ww = 1, wh = 1, fw = 1, fh = 1;
  glfwGetWindowSize(window, &ww, &wh);
  glfwGetFramebufferSize(window, &fw, &fh);
  x *= static_cast<double>(fw) / std::max(ww, 1);
  y *= static_cast<double>(fh) / std::max(wh, 1);
  shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
          glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool other = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                     glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  if (left && !left_down && !io.WantCaptureMouse) {
    Press(x, y);
  } else if (other && !left_down && !io.WantCaptureMouse) {
    mouse_x = x;
    mouse_y = y;
    left_down = true;
    drag = Drag::kPan;
  } else if (!left && !other && left_down) {
    ReleaseButton();
  } else {
    Move(x, y);
  }
  mouse_x = x;
  mouse_y = y;
}

std::vector<int> Viewer::Impl::MaterialTargets() const {
  if (selected < 0) return {};
  if (material_scope == MaterialScope::kLevel)
    return BranchesOfLevel(tree, tree.branches[selected].level);
  return {selected};
}

void Viewer::Impl::EditMaterial(MaterialProperty property, double value,
                                const std::vector<int>& branches) {
  const int n = EditMaterials(*sim, branches, property, value);
  spdlog::info("view: {} = {} on {} branch{}", ToString(property), value, n, n == 1 ? "" : "es");
}

}  // namespace simtree::viewer
