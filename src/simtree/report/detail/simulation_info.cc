#include "simtree/report/detail/simulation_info.h"

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"

namespace simtree::report {

std::optional<SimulationInfo> ReadSimulationInfo(const ResultFolder& folder) {
  if (!folder.HasFile("simulate/simulation.json")) return std::nullopt;
  try {
    const JsonDocument doc = ReadJsonDocument(folder.Path("simulate/simulation.json"));
    const JsonNode root = doc.root();
    SimulationInfo info;
    if (auto v = FindValue(root, "fps")) info.fps = v->Number();
    if (auto v = FindValue(root, "duration_s")) info.duration_s = v->Number();
    if (auto v = FindValue(root, "tree"); v && v->json().is_string()) info.tree = v->String();
    if (auto v = FindValue(root, "integrator"); v && v->json().is_string())
      info.integrator = v->String();
    info.wind = FindValue(root, "wind").has_value();  // "wind": null without wind
    if (auto p = FindValue(root, "pull"); p && p->json().is_object()) {
      SimulationInfo::Pull pull;
      if (auto v = FindValue(*p, "point")) pull.point = v->Vector3();
      if (auto v = FindValue(*p, "anchor")) pull.anchor = v->Vector3();
      if (auto v = FindValue(*p, "hold_s")) pull.hold_s = v->Number();
      if (auto v = FindValue(*p, "release_s")) pull.release_s = v->Number();
      if (auto v = FindValue(*p, "tension_n")) pull.tension_n = v->Number();
      if (auto v = FindValue(*p, "branch")) pull.branch = v->Integer();
      info.pull = pull;
    }
    return info;
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace simtree::report
