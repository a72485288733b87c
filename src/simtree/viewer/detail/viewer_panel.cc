#include <imgui.h>

#include "simtree/viewer/detail/viewer_impl.h"

namespace simtree::viewer {

void Viewer::Impl::DrawPanel() {
  if (panel) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(panel_width, ImGui::GetIO().DisplaySize.y));
    ImGui::Begin("simtree", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::Text("%s", tree.metadata.source.empty() ? "tree" : tree.metadata.source.c_str());
    ImGui::Text("%d branches, %d nodes, %d leaves", tree.size(), tree.NodeCount(),
                scene->leaf_count());
    ImGui::Text("%.1f ms a frame (%.0f fps), %lld triangles", recent_frame_ms,
                recent_frame_ms > 0 ? 1000.0 / recent_frame_ms : 0.0,
                static_cast<long long>(stats.triangles));
    DrawSimulationSection();
    DrawPullSection();
    DrawWindSection();
    DrawMaterialSection();
    DrawDisplaySection();
    if (options.measured) DrawPlaybackSection();
    if (ImGui::Button("Screenshot")) pending_screenshots.push_back(NextScreenshotPath());
    ImGui::SameLine();
    ImGui::TextDisabled("(p)");
    ImGui::End();
  }
  DrawHoverTooltip();
}

void Viewer::Impl::DrawSimulationSection() {
  if (!ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::Button(playing ? "Pause" : "Play")) playing = !playing;
  ImGui::SameLine();
  if (ImGui::Button("Step")) {
    playing = false;
    step_once = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Reset")) Reset();
  ImGui::Text("t = %.2f s, energy %.3g J", sim->time(), sim->Energy());
}

void Viewer::Impl::DrawPullSection() {
  if (!ImGui::CollapsingHeader("Pull", ImGuiTreeNodeFlags_DefaultOpen)) return;
  int mode = static_cast<int>(grab_mode);
  ImGui::RadioButton("follow the cursor", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("force", &mode, 1);
  grab_mode = static_cast<GrabMode>(mode);
  if (grab_mode == GrabMode::kForce) {
    ImGui::SliderFloat("N per m", &force_per_metre, 1.0f, 2000.0f, "%.0f",
                       ImGuiSliderFlags_Logarithmic);
  }
  ImGui::SliderFloat("max N", &max_tension, 1.0f, 800.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
  if (grab_rope >= 0 && sim->HasRope(grab_rope)) {
    ImGui::Text("rope on branch %d: %.1f N", selected, sim->RopeTension(grab_rope));
  } else {
    ImGui::TextDisabled("drag a branch to pull it");
  }
  if (ImGui::Button("Release all")) {
    sim->ReleaseAllRopes();
    grab_rope = -1;
  }
}

void Viewer::Impl::DrawWindSection() {
  if (!ImGui::CollapsingHeader("Wind", ImGuiTreeNodeFlags_DefaultOpen)) return;
  bool on = sim->wind().enabled;
  bool changed = ImGui::Checkbox("wind", &on);
  changed |= ImGui::SliderFloat("m/s", &wind_speed, 0.0f, 20.0f, "%.1f");
  changed |= ImGui::SliderFloat("heading", &wind_heading_deg, -180.0f, 180.0f, "%.0f deg");
  if (changed) SetWind(on);
}

// The picked branch's frequency, damping and stiffness, applied live to it or to its level.
void Viewer::Impl::DrawMaterialSection() {
  if (!ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (selected < 0) {
    ImGui::TextDisabled("pick a branch to tune it");
    return;
  }
  const Branch& b = tree.branches[selected];
  const Material& m = sim->material(selected);
  ImGui::Text("branch %d, level %d, %s", selected, b.level, ToString(m.source));
  int scope = static_cast<int>(material_scope);
  ImGui::RadioButton("this branch", &scope, static_cast<int>(MaterialScope::kBranch));
  ImGui::SameLine();
  ImGui::RadioButton("its level", &scope, static_cast<int>(MaterialScope::kLevel));
  material_scope = static_cast<MaterialScope>(scope);
  for (const MaterialProperty p :
       {MaterialProperty::kFrequency, MaterialProperty::kDamping, MaterialProperty::kStiffness}) {
    const PropertyRange range = RangeOf(p);
    float value = static_cast<float>(PropertyValue(m, p));
    const char* label = p == MaterialProperty::kFrequency ? "f (Hz)"
                        : p == MaterialProperty::kDamping ? "damping"
                                                          : "k (N/m)";
    if (ImGui::SliderFloat(label, &value, static_cast<float>(range.min),
                           static_cast<float>(range.max), "%.4g", ImGuiSliderFlags_Logarithmic)) {
      EditMaterial(p, value, MaterialTargets());
    }
  }
}

void Viewer::Impl::DrawDisplaySection() {
  if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
  bool leaves = style.leaves;
  if (!scene->has_leaves()) {
    ImGui::TextDisabled("no leaves");
    if (!leaf_error.empty()) ImGui::TextWrapped("%s", leaf_error.c_str());
  } else if (ImGui::Checkbox("leaves", &leaves)) {
    SetLeaves(leaves);
  }
  ImGui::Checkbox("grid", &style.grid);
  ImGui::SameLine();
  ImGui::Checkbox("markers", &show_markers);
  int colouring = static_cast<int>(style.colouring);
  if (ImGui::Combo("colour", &colouring, "bark\0level\0material source\0")) {
    style.colouring = static_cast<BranchColouring>(colouring);
  }
}

// Measured markers against the simulated ones at the simulation's time.
void Viewer::Impl::DrawPlaybackSection() {
  if (!ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (comparison && !comparison->markers.empty()) {
    ImGui::Text("%zu markers: RMS %.1f mm, max %.1f mm", comparison->markers.size(),
                1000.0 * comparison->rms_error_m, 1000.0 * comparison->max_error_m);
    for (size_t i = 0; i < comparison->markers.size() && i < 16; ++i) {
      const MarkerError& e = comparison->markers[i];
      ImGui::Text("%-8s %7.1f mm", e.label.c_str(), 1000.0 * e.error_m);
    }
  } else {
    ImGui::TextDisabled("no measured marker at t = %.2f s", sim->time());
  }
  ImGui::TextDisabled("red: measured, blue: simulated");
}

void Viewer::Impl::DrawHoverTooltip() {
  if (hovered < 0 || drag != Drag::kNone || ImGui::GetIO().WantCaptureMouse) return;
  const Material& m = sim->material(hovered);
  const Branch& b = tree.branches[hovered];
  ImGui::BeginTooltip();
  ImGui::Text("branch %d, level %d", hovered, b.level);
  ImGui::Text("f %.3g Hz, damping %.3g, k %.4g N/m", m.modes[0].frequency_hz,
              m.modes[0].damping_ratio, m.stiffness);
  ImGui::Text("%s", m.source == MaterialSource::kMeasured       ? "measured"
                    : m.source == MaterialSource::kInterpolated ? "interpolated"
                    : m.source == MaterialSource::kAssumed      ? "assumed (typical, not measured)"
                                                                : "default (not measured)");
  ImGui::EndTooltip();
}

}  // namespace simtree::viewer
