#include "simtree/identification/materials_file.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/units.h"

namespace simtree::identification {
namespace {

using ojson = nlohmann::ordered_json;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

ojson Number(double x) { return std::isfinite(x) ? ojson(x) : ojson(nullptr); }

ojson EstimateToJson(const ModalEstimate& e) {
  ojson j;
  j["status"] = ToString(e.status);
  if (!e.message.empty()) j["message"] = e.message;
  j["frequency_hz"] = Number(e.frequency_hz);
  j["damping_ratio"] = Number(e.damping_ratio);
  j["frequency_std_hz"] = Number(e.frequency_std_hz);
  j["damping_std"] = Number(e.damping_std);
  j["amplitude"] = Number(e.amplitude);
  return j;
}

EstimateStatus ParseStatus(const JsonNode& node) {
  const std::string name = node.String();
  for (int k = 0; k <= static_cast<int>(EstimateStatus::kMissingMarker); ++k) {
    if (name == ToString(static_cast<EstimateStatus>(k))) return static_cast<EstimateStatus>(k);
  }
  node.Fail(fmt::format("unknown status \"{}\"", name));
}

// A number that may be missing or null (NaN then).
double NullableNumber(const JsonNode& obj, const std::string& key) {
  const std::optional<JsonNode> value = obj.Find(key);
  return value && !value->is_null() ? value->Number() : kNaN;
}

// `kind` is the estimator that gave the estimate: a fit writes null for a standard deviation its
// covariance cannot give (infinite in memory: a pole it cannot resolve), a spectral estimator
// because it gives none, so the fit's null reads back as infinite.
ModalEstimate EstimateFromJson(const JsonNode& j, EstimatorKind kind) {
  j.ExpectObject();
  ModalEstimate e;
  e.status = ParseStatus(j.Field("status"));
  if (const auto message = j.Find("message")) e.message = message->String();
  e.frequency_hz = NullableNumber(j, "frequency_hz");
  e.damping_ratio = NullableNumber(j, "damping_ratio");
  e.frequency_std_hz = NullableNumber(j, "frequency_std_hz");
  e.damping_std = NullableNumber(j, "damping_std");
  if (kind == EstimatorKind::kDampedSinusoidFit && e.status == EstimateStatus::kOk) {
    if (std::isnan(e.frequency_std_hz)) e.frequency_std_hz = kInfinity;
    if (std::isnan(e.damping_std)) e.damping_std = kInfinity;
  }
  e.amplitude = NullableNumber(j, "amplitude");
  if (e.status == EstimateStatus::kOk && (!e.has_frequency() || !e.has_damping())) {
    j.Fail("status \"ok\" needs a frequency_hz and a damping_ratio");
  }
  if (e.has_frequency() && e.frequency_hz <= 0) {
    j.FailAt(Member(j.at(), "frequency_hz"), fmt::format("expected > 0, got {}", e.frequency_hz));
  }
  if (e.has_damping() && (e.damping_ratio <= 0 || e.damping_ratio >= 1)) {
    j.FailAt(Member(j.at(), "damping_ratio"),
             fmt::format("expected in (0, 1), got {}", e.damping_ratio));
  }
  return e;
}

EstimatorKind EstimatorFromJson(const JsonNode& node) {
  const std::string name = node.String();
  const auto kind = ParseEstimatorKind(name);
  if (!kind) node.Fail(fmt::format("unknown estimator \"{}\"", name));
  return *kind;
}

// The "record" object: where the values came from.
void ReadRecord(const JsonNode& rec, MaterialsFile& m) {
  rec.ExpectObject();
  if (const auto v = rec.Find("trajectories")) m.trajectories = v->String();
  m.frame_rate_hz = NullableNumber(rec, "frame_rate_hz");
  m.release_time_s = NullableNumber(rec, "release_time_s");
  if (const auto v = rec.Find("release_detected")) m.release_detected = v->Bool();
  if (const auto v = rec.Find("release_note")) m.release_note = v->String();
  if (const auto w = rec.Find("window_s")) {
    if (w->size() != 2) w->Fail("expected [start, end] in seconds");
    m.window_start_s = w->Item(0).is_null() ? kNaN : w->Item(0).Number();
    m.window_end_s = w->Item(1).is_null() ? kNaN : w->Item(1).Number();
  }
}

LinkModeShare ModeShareFromJson(const JsonNode& j) {
  j.ExpectObject();
  LinkModeShare m;
  const JsonNode f = j.Field("frequency_hz"), z = j.Field("damping_ratio");
  m.frequency_hz = f.Number();
  m.damping_ratio = z.Number();
  if (!(m.frequency_hz > 0)) f.Fail("expected > 0");
  if (!(m.damping_ratio > 0 && m.damping_ratio < 1)) z.Fail("expected in (0, 1)");
  m.frequency_std_hz = NullableNumber(j, "frequency_std_hz");
  m.damping_std = NullableNumber(j, "damping_std");
  m.amplitude = NullableNumber(j, "amplitude");
  m.strength = NullableNumber(j, "strength");
  m.share = NullableNumber(j, "share");
  m.participation = NullableNumber(j, "participation");
  return m;
}

ojson ModeShareToJson(const LinkModeShare& m) {
  return {{"frequency_hz", Number(m.frequency_hz)},
          {"damping_ratio", Number(m.damping_ratio)},
          {"frequency_std_hz", Number(m.frequency_std_hz)},
          {"damping_std", Number(m.damping_std)},
          {"amplitude", Number(m.amplitude)},
          {"strength", Number(m.strength)},
          {"share", Number(m.share)},
          {"participation", Number(m.participation)}};
}

// `estimator`: the file's, which gave the link's value, planes and pole readings.
LinkMaterial LinkFromJson(const JsonNode& j, EstimatorKind estimator) {
  j.ExpectObject();
  LinkMaterial l;
  l.child = j.Integer("child");
  l.parent = j.Integer("parent");
  if (const auto label = j.Find("label")) l.label = label->String();
  if (const auto branch = j.Find("branch"); branch && !branch->is_null()) {
    l.branch = branch->Integer();
  }
  if (const auto kind = j.Find("kind")) {
    const std::string name = kind->String();
    if (name == ToString(DeflectionKind::kDisplacement)) {
      l.kind = DeflectionKind::kDisplacement;
    } else if (name != ToString(DeflectionKind::kRelativeAngle)) {
      kind->Fail(fmt::format("expected relative_angle or displacement, got \"{}\"", name));
    }
  }
  l.value = EstimateFromJson(j, estimator);
  if (const auto planes = j.Find("planes")) {
    if (planes->size() != 2) planes->Fail("expected 2 planes (u, w)");
    for (int c = 0; c < 2; ++c) l.planes[c] = EstimateFromJson(planes->Item(c), estimator);
  } else {
    l.planes = {l.value, l.value};
  }
  if (const auto estimators = j.Find("estimators")) {
    estimators->ExpectObject();
    for (const auto& [name, e] : estimators->json().items()) {
      const JsonNode node(e, estimators->source(), Member(estimators->at(), name));
      const auto kind = ParseEstimatorKind(name);
      if (!kind) node.Fail("unknown estimator");
      l.estimators.emplace_back(*kind, EstimateFromJson(node, *kind));
    }
  }
  if (const auto poles = j.Find("poles"); poles && !poles->is_null()) {
    poles->ExpectObject();
    l.poles = poles->Field("used").String();
    if (l.poles != "shared" && l.poles != "own") {
      poles->Fail(fmt::format("used: expected shared or own, got \"{}\"", l.poles));
    }
    if (const auto why = poles->Find("why")) l.poles_why = why->String();
    if (const auto shared = poles->Find("shared"))
      l.shared_reading = EstimateFromJson(*shared, estimator);
    if (const auto own = poles->Find("own")) l.own_reading = EstimateFromJson(*own, estimator);
  }
  if (const auto modes = j.Find("modes")) {
    for (const JsonNode& m : modes->Items()) l.modes.push_back(ModeShareFromJson(m));
  }
  if (const auto mode = j.Find("branch_mode"); mode && !mode->is_null()) {
    l.branch_mode = EstimateFromJson(*mode, estimator);
    l.branch_participation = NullableNumber(*mode, "participation");
    l.most_participating_hz = NullableNumber(*mode, "most_participating_hz");
    if (const auto why = mode->Find("why")) l.branch_mode_why = why->String();
    if (const auto planes = mode->Find("planes")) {
      if (planes->size() != 2) planes->Fail("expected 2 planes (u, w)");
      for (int c = 0; c < 2; ++c) l.branch_planes[c] = EstimateFromJson(planes->Item(c), estimator);
    } else {
      l.branch_planes = {l.branch_mode, l.branch_mode};
    }
  }
  return l;
}

BranchMaterial BranchFromJson(const JsonNode& j) {
  j.ExpectObject();
  BranchMaterial b;
  const JsonNode branch = j.Field("branch");
  b.branch = branch.Integer();
  if (b.branch < 0) branch.Fail("expected a branch id >= 0");
  if (const auto marker = j.Find("marker")) b.link_child = marker->Integer();
  const JsonNode modes = j.Field("modes");
  if (modes.size() != 3) modes.Fail("expected 3 modes: bend_u, bend_w, twist_v");
  for (int k = 0; k < 3; ++k) {
    const JsonNode mj = modes.Item(k).ExpectObject();
    const JsonNode kind = mj.Field("kind");
    b.modes[k].kind = ParseModeKind(kind.String(), j.source(), kind.at());
    if (b.modes[k].kind != static_cast<ModeKind>(k)) {
      kind.Fail("expected the order bend_u, bend_w, twist_v");
    }
    const JsonNode f = mj.Field("frequency_hz"), z = mj.Field("damping_ratio");
    b.modes[k].frequency_hz = f.Number();
    b.modes[k].damping_ratio = z.Number();
    if (!(b.modes[k].frequency_hz > 0)) f.Fail("expected > 0");
    if (!(b.modes[k].damping_ratio > 0 && b.modes[k].damping_ratio < 1)) {
      z.Fail("expected in (0, 1)");
    }
    if (const auto assumed = mj.Find("assumed")) b.assumed[k] = assumed->Bool();
  }
  b.frequency_std_hz = NullableNumber(j, "frequency_std_hz");
  b.damping_std = NullableNumber(j, "damping_std");
  return b;
}

// How sure a link's value is, for choosing among links on one branch (smaller is surer).
double Uncertainty(const LinkMaterial& link) {
  if (std::isfinite(link.value.frequency_std_hz)) {
    return link.value.frequency_std_hz / link.value.frequency_hz;
  }
  return 1.0 / (1.0 + (std::isfinite(link.value.amplitude) ? link.value.amplitude : 0.0));
}

}  // namespace

MaterialsFile MaterialsFromIdentification(const IdentificationResult& result,
                                          const std::string& trajectories_name) {
  MaterialsFile m;
  m.estimator = result.estimator;
  m.trajectories = trajectories_name;
  m.frame_rate_hz = result.frame_rate_hz;
  m.release_time_s = result.release.time_s;
  m.release_detected = result.release.found();
  m.release_note = result.release.note;
  m.window_start_s = result.window_start_s;
  m.window_end_s = result.window_end_s;
  m.ranges = result.Ranges();
  for (const LinkIdentification& link : result.links) {
    LinkMaterial l;
    l.child = link.deflection.link.child;
    l.parent = link.deflection.link.parent;
    l.label = link.deflection.link.label;
    l.branch = link.deflection.link.branch;
    l.kind = link.deflection.kind;
    l.value = link.value;
    if (!link.estimates.empty()) {
      const SignalEstimate& chosen = link.estimates.front();
      for (int c = 0; c < 2 && c < static_cast<int>(chosen.per_channel.size()); ++c) {
        l.planes[c] = chosen.per_channel[c];
      }
      for (const SignalEstimate& e : link.estimates)
        l.estimators.emplace_back(e.estimator, e.dominant);
      if (!link.poles.why.empty()) {
        l.poles = link.poles.shared ? "shared" : "own";
        l.poles_why = link.poles.why;
        l.shared_reading = link.poles.joint;
        l.own_reading = link.poles.own;
      }
      l.modes = link.modes;
      if (link.branch_mode.value.status == EstimateStatus::kOk) {
        l.branch_mode = link.branch_mode.value;
        l.branch_planes = link.branch_mode.planes;
        l.branch_participation = link.branch_mode.participation;
        l.most_participating_hz = link.branch_mode.most_participating_hz;
        l.branch_mode_why = link.branch_mode.why;
      }
    } else {
      l.planes = {link.value, link.value};
    }
    m.links.push_back(std::move(l));
  }
  AssignBranchMaterials(m);
  return m;
}

void AssignBranchMaterials(MaterialsFile& m, const std::vector<int>& marker_branch) {
  std::map<int, const LinkMaterial*> best;
  for (const LinkMaterial& link : m.links) {
    if (link.value.status != EstimateStatus::kOk) continue;
    int branch = link.branch.value_or(-1);
    if (branch < 0 && link.child >= 0 && link.child < static_cast<int>(marker_branch.size())) {
      branch = marker_branch[link.child];
    }
    if (branch < 0) continue;
    auto it = best.find(branch);
    if (it == best.end() || Uncertainty(link) < Uncertainty(*it->second)) best[branch] = &link;
  }
  m.branches.clear();
  for (const auto& [branch, link] : best) {
    BranchMaterial b;
    b.branch = branch;
    b.link_child = link->child;
    // The branch's own mode (its participation) when the link carries joint poles, else the
    // link's dominant mode.
    const bool own_mode =
        link->branch_mode.status == EstimateStatus::kOk && link->branch_mode.has_frequency();
    const ModalEstimate& value = own_mode ? link->branch_mode : link->value;
    const std::array<ModalEstimate, 2>& planes = own_mode ? link->branch_planes : link->planes;
    b.frequency_std_hz = value.frequency_std_hz;
    b.damping_std = value.damping_std;
    for (int k = 0; k < 3; ++k) {
      b.modes[k].kind = static_cast<ModeKind>(k);
      // A bending mode takes its own plane's reading when the link is an angle (its planes are
      // the branch's u and w) and that reading exists; otherwise the dominant value, assumed.
      const ModalEstimate* e = &value;
      b.assumed[k] = true;
      if (k < 2 && link->kind == DeflectionKind::kRelativeAngle &&
          planes[k].status == EstimateStatus::kOk && planes[k].has_frequency()) {
        e = &planes[k];
        b.assumed[k] = false;
      }
      b.modes[k].frequency_hz = e->frequency_hz;
      b.modes[k].damping_ratio = e->damping_ratio;
    }
    m.branches.push_back(b);
  }
}

nlohmann::ordered_json MaterialsToJson(const MaterialsFile& m) {
  ojson doc;
  doc["format"] = kMaterialsFormat;
  doc["version"] = kMaterialsFormatVersion;
  doc["estimator"] = ToString(m.estimator);
  doc["record"] = {{"trajectories", m.trajectories},
                   {"frame_rate_hz", Number(m.frame_rate_hz)},
                   {"release_time_s", Number(m.release_time_s)},
                   {"release_detected", m.release_detected},
                   {"release_note", m.release_note},
                   {"window_s", {Number(m.window_start_s), Number(m.window_end_s)}}};
  const MaterialRanges& r = m.ranges;
  doc["summary"] = {
      {"links", r.links},
      {"measured", r.measured},
      {"frequency_hz", {Number(r.min_frequency_hz), Number(r.max_frequency_hz)}},
      {"damping_ratio", {Number(r.min_damping), Number(r.max_damping)}},
      {"max_relative_std",
       {{"frequency", r.bounds.max_frequency_relative_std},
        {"damping", r.bounds.max_damping_relative_std}}},
      {"in_range", {{"frequency", r.frequency_count}, {"damping", r.damping_count}}},
      {"uncertain", r.uncertain},
      {"all_frequency_hz", {Number(r.all_min_frequency_hz), Number(r.all_max_frequency_hz)}},
      {"all_damping_ratio", {Number(r.all_min_damping), Number(r.all_max_damping)}}};
  ojson links = ojson::array();
  for (const LinkMaterial& l : m.links) {
    ojson j;
    j["child"] = l.child;
    j["parent"] = l.parent;
    j["label"] = l.label;
    j["branch"] = l.branch ? ojson(*l.branch) : ojson(nullptr);
    j["kind"] = ToString(l.kind);
    const ojson value = EstimateToJson(l.value);  // named: items() of a temporary would dangle
    for (const auto& item : value.items()) j[item.key()] = item.value();
    ojson planes = ojson::array();
    for (int c = 0; c < 2; ++c) planes.push_back(EstimateToJson(l.planes[c]));
    j["planes"] = std::move(planes);
    ojson estimators = ojson::object();
    for (const auto& [kind, e] : l.estimators) estimators[ToString(kind)] = EstimateToJson(e);
    j["estimators"] = std::move(estimators);
    j["poles"] = l.poles.empty() ? ojson(nullptr)
                                 : ojson{{"used", l.poles},
                                         {"why", l.poles_why},
                                         {"shared", EstimateToJson(l.shared_reading)},
                                         {"own", EstimateToJson(l.own_reading)}};
    if (!l.modes.empty()) {
      ojson modes = ojson::array();
      for (const LinkModeShare& share : l.modes) modes.push_back(ModeShareToJson(share));
      j["modes"] = std::move(modes);
    }
    if (l.branch_mode.has_frequency()) {
      ojson mode = EstimateToJson(l.branch_mode);
      mode["participation"] = Number(l.branch_participation);
      mode["most_participating_hz"] = Number(l.most_participating_hz);
      mode["why"] = l.branch_mode_why;
      mode["planes"] = {EstimateToJson(l.branch_planes[0]), EstimateToJson(l.branch_planes[1])};
      j["branch_mode"] = std::move(mode);
    }
    links.push_back(std::move(j));
  }
  doc["links"] = std::move(links);
  ojson branches = ojson::array();
  for (const BranchMaterial& b : m.branches) {
    ojson modes = ojson::array();
    for (int k = 0; k < 3; ++k) {
      modes.push_back({{"kind", ToString(b.modes[k].kind)},
                       {"frequency_hz", Number(b.modes[k].frequency_hz)},
                       {"damping_ratio", Number(b.modes[k].damping_ratio)},
                       {"assumed", b.assumed[k]}});
    }
    branches.push_back({{"branch", b.branch},
                        {"marker", b.link_child},
                        {"modes", std::move(modes)},
                        {"frequency_std_hz", Number(b.frequency_std_hz)},
                        {"damping_std", Number(b.damping_std)}});
  }
  doc["branches"] = std::move(branches);
  return doc;
}

MaterialsFile MaterialsFromJson(const nlohmann::json& value, const std::string& source) {
  const JsonNode doc(value, source);
  doc.ExpectObject();
  CheckFormat(doc, kMaterialsFormat, kMaterialsFormatVersion);
  MaterialsFile m;
  m.estimator = EstimatorFromJson(doc.Field("estimator"));
  if (const auto record = doc.Find("record")) ReadRecord(*record, m);
  for (const JsonNode& link : doc.Field("links").Items())
    m.links.push_back(LinkFromJson(link, m.estimator));
  // The summary is recomputed from the links, not read: it cannot disagree with them.
  std::vector<LabeledEstimate> values;
  for (const LinkMaterial& l : m.links) values.push_back({l.label, l.value});
  m.ranges = ComputeRanges(values);
  if (const auto branches = doc.Find("branches")) {
    for (const JsonNode& branch : branches->Items()) m.branches.push_back(BranchFromJson(branch));
  }
  return m;
}

MaterialsFile ReadMaterialsJson(const std::filesystem::path& path) {
  const JsonDocument doc = ReadJsonDocument(path);
  return MaterialsFromJson(doc.value, doc.source);
}

void WriteMaterialsJson(const MaterialsFile& materials, const std::filesystem::path& path) {
  WriteFileAtomically(path, MaterialsToJson(materials).dump(1) + "\n");
}

}  // namespace simtree::identification
