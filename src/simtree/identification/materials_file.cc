#include "simtree/identification/materials_file.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/tree_json.h"

namespace simtree::identification {
namespace {

using ojson = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

EstimateStatus ParseStatus(const JsonReader& r, const nlohmann::json& v, const std::string& at) {
  const std::string name = r.String(v, at);
  for (int k = 0; k <= static_cast<int>(EstimateStatus::kMissingMarker); ++k) {
    if (name == ToString(static_cast<EstimateStatus>(k))) return static_cast<EstimateStatus>(k);
  }
  r.Fail(at, fmt::format("unknown status \"{}\"", name));
}

double NullableNumber(const JsonReader& r, const nlohmann::json& obj, const std::string& key,
                      const std::string& at) {
  if (!r.Has(obj, key) || obj[key].is_null()) return kNaN;
  return r.Number(obj[key], Member(at, key));
}

ModalEstimate EstimateFromJson(const JsonReader& r, const nlohmann::json& j,
                               const std::string& at) {
  r.Object(j, at);
  ModalEstimate e;
  e.status = ParseStatus(r, r.Field(j, "status", at), Member(at, "status"));
  if (r.Has(j, "message")) e.message = r.String(j["message"], Member(at, "message"));
  e.frequency_hz = NullableNumber(r, j, "frequency_hz", at);
  e.damping_ratio = NullableNumber(r, j, "damping_ratio", at);
  e.frequency_std_hz = NullableNumber(r, j, "frequency_std_hz", at);
  e.damping_std = NullableNumber(r, j, "damping_std", at);
  e.amplitude = NullableNumber(r, j, "amplitude", at);
  if (e.status == EstimateStatus::kOk && (!e.has_frequency() || !e.has_damping())) {
    r.Fail(at, "status \"ok\" needs a frequency_hz and a damping_ratio");
  }
  if (e.has_frequency() && e.frequency_hz <= 0) {
    r.Fail(Member(at, "frequency_hz"), fmt::format("expected > 0, got {}", e.frequency_hz));
  }
  if (e.has_damping() && (e.damping_ratio <= 0 || e.damping_ratio >= 1)) {
    r.Fail(Member(at, "damping_ratio"), fmt::format("expected in (0, 1), got {}", e.damping_ratio));
  }
  return e;
}

bool Boolean(const JsonReader& r, const nlohmann::json& v, const std::string& at) {
  if (!v.is_boolean()) r.Fail(at, fmt::format("expected true or false, got {}", v.dump()));
  return v.get<bool>();
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
  m.estimator = ToString(result.estimator);
  m.trajectories = trajectories_name;
  m.frame_rate_hz = result.frame_rate_hz;
  m.release_time_s = result.release.time_s;
  m.release_detected = result.release.found;
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
    b.frequency_std_hz = link->value.frequency_std_hz;
    b.damping_std = link->value.damping_std;
    for (int k = 0; k < 3; ++k) {
      b.modes[k].kind = static_cast<ModeKind>(k);
      // A bending mode takes its own plane's reading when the link is an angle (its planes are
      // the branch's u and w) and that reading exists; otherwise the dominant value, assumed.
      const ModalEstimate* e = &link->value;
      b.assumed[k] = true;
      if (k < 2 && link->kind == DeflectionKind::kRelativeAngle &&
          link->planes[k].status == EstimateStatus::kOk) {
        e = &link->planes[k];
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
  doc["estimator"] = m.estimator;
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

MaterialsFile MaterialsFromJson(const nlohmann::json& doc, const std::string& source) {
  const JsonReader r(source);
  r.Object(doc, "");
  const std::string format = r.String(r.Field(doc, "format", ""), "format");
  if (format != kMaterialsFormat) {
    r.Fail("format", fmt::format("expected \"{}\", got \"{}\"", kMaterialsFormat, format));
  }
  const int version = r.Integer(r.Field(doc, "version", ""), "version");
  if (version != kMaterialsFormatVersion) {
    r.Fail("version", fmt::format("expected {}, got {}", kMaterialsFormatVersion, version));
  }
  MaterialsFile m;
  m.estimator = r.String(r.Field(doc, "estimator", ""), "estimator");
  if (r.Has(doc, "record")) {
    const auto& rec = r.Object(doc["record"], "record");
    if (r.Has(rec, "trajectories"))
      m.trajectories = r.String(rec["trajectories"], "record.trajectories");
    m.frame_rate_hz = NullableNumber(r, rec, "frame_rate_hz", "record");
    m.release_time_s = NullableNumber(r, rec, "release_time_s", "record");
    if (r.Has(rec, "release_detected"))
      m.release_detected = Boolean(r, rec["release_detected"], "record.release_detected");
    if (r.Has(rec, "release_note"))
      m.release_note = r.String(rec["release_note"], "record.release_note");
    if (r.Has(rec, "window_s")) {
      const auto& w = r.Array(rec["window_s"], "record.window_s");
      if (w.size() != 2) r.Fail("record.window_s", "expected [start, end] in seconds");
      m.window_start_s = w[0].is_null() ? kNaN : r.Number(w[0], "record.window_s[0]");
      m.window_end_s = w[1].is_null() ? kNaN : r.Number(w[1], "record.window_s[1]");
    }
  }
  const auto& links = r.Array(r.Field(doc, "links", ""), "links");
  for (size_t i = 0; i < links.size(); ++i) {
    const std::string at = Element("links", i);
    const auto& j = r.Object(links[i], at);
    LinkMaterial l;
    l.child = r.Integer(r.Field(j, "child", at), Member(at, "child"));
    l.parent = r.Integer(r.Field(j, "parent", at), Member(at, "parent"));
    if (r.Has(j, "label")) l.label = r.String(j["label"], Member(at, "label"));
    if (r.Has(j, "branch") && !j["branch"].is_null()) {
      l.branch = r.Integer(j["branch"], Member(at, "branch"));
    }
    if (r.Has(j, "kind")) {
      const std::string kind = r.String(j["kind"], Member(at, "kind"));
      if (kind == ToString(DeflectionKind::kDisplacement)) {
        l.kind = DeflectionKind::kDisplacement;
      } else if (kind != ToString(DeflectionKind::kRelativeAngle)) {
        r.Fail(Member(at, "kind"),
               fmt::format("expected relative_angle or displacement, got \"{}\"", kind));
      }
    }
    l.value = EstimateFromJson(r, j, at);
    if (r.Has(j, "planes")) {
      const auto& planes = r.Array(j["planes"], Member(at, "planes"));
      if (planes.size() != 2) r.Fail(Member(at, "planes"), "expected 2 planes (u, w)");
      for (int c = 0; c < 2; ++c) {
        l.planes[c] = EstimateFromJson(r, planes[c], Element(Member(at, "planes"), c));
      }
    } else {
      l.planes = {l.value, l.value};
    }
    if (r.Has(j, "estimators")) {
      for (const auto& [name, e] : r.Object(j["estimators"], Member(at, "estimators")).items()) {
        const auto kind = ParseEstimatorKind(name);
        if (!kind) r.Fail(Member(Member(at, "estimators"), name), "unknown estimator");
        l.estimators.emplace_back(*kind,
                                  EstimateFromJson(r, e, Member(Member(at, "estimators"), name)));
      }
    }
    m.links.push_back(std::move(l));
  }
  std::vector<LabeledEstimate> values;
  for (const LinkMaterial& l : m.links) values.push_back({l.label, l.value});
  m.ranges = ComputeRanges(values);
  if (r.Has(doc, "branches")) {
    const auto& branches = r.Array(doc["branches"], "branches");
    for (size_t i = 0; i < branches.size(); ++i) {
      const std::string at = Element("branches", i);
      const auto& j = r.Object(branches[i], at);
      BranchMaterial b;
      b.branch = r.Integer(r.Field(j, "branch", at), Member(at, "branch"));
      if (b.branch < 0) r.Fail(Member(at, "branch"), "expected a branch id >= 0");
      if (r.Has(j, "marker")) b.link_child = r.Integer(j["marker"], Member(at, "marker"));
      const auto& modes = r.Array(r.Field(j, "modes", at), Member(at, "modes"));
      if (modes.size() != 3)
        r.Fail(Member(at, "modes"), "expected 3 modes: bend_u, bend_w, twist_v");
      for (int k = 0; k < 3; ++k) {
        const std::string mat = Element(Member(at, "modes"), k);
        const auto& mj = r.Object(modes[k], mat);
        b.modes[k].kind = ParseModeKind(r.String(r.Field(mj, "kind", mat), Member(mat, "kind")),
                                        source, Member(mat, "kind"));
        if (b.modes[k].kind != static_cast<ModeKind>(k)) {
          r.Fail(Member(mat, "kind"), "expected the order bend_u, bend_w, twist_v");
        }
        b.modes[k].frequency_hz =
            r.Number(r.Field(mj, "frequency_hz", mat), Member(mat, "frequency_hz"));
        b.modes[k].damping_ratio =
            r.Number(r.Field(mj, "damping_ratio", mat), Member(mat, "damping_ratio"));
        if (!(b.modes[k].frequency_hz > 0)) r.Fail(Member(mat, "frequency_hz"), "expected > 0");
        if (!(b.modes[k].damping_ratio > 0 && b.modes[k].damping_ratio < 1)) {
          r.Fail(Member(mat, "damping_ratio"), "expected in (0, 1)");
        }
        if (r.Has(mj, "assumed")) b.assumed[k] = Boolean(r, mj["assumed"], Member(mat, "assumed"));
      }
      b.frequency_std_hz = NullableNumber(r, j, "frequency_std_hz", at);
      b.damping_std = NullableNumber(r, j, "damping_std", at);
      m.branches.push_back(b);
    }
  }
  return m;
}

MaterialsFile ReadMaterialsJson(const std::filesystem::path& path) {
  return MaterialsFromJson(ParseJson(ReadFile(path), path.string()), path.string());
}

void WriteMaterialsJson(const MaterialsFile& materials, const std::filesystem::path& path) {
  WriteFileAtomically(path, MaterialsToJson(materials).dump(1) + "\n");
}

}  // namespace simtree::identification
