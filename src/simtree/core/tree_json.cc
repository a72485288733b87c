#include "simtree/core/tree_json.h"

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/json_util.h"

namespace simtree {
namespace {

using ojson = nlohmann::ordered_json;

ojson VectorJson(const Eigen::Vector3d& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson MaterialJson(const Material& m) {
  ojson modes = ojson::array();
  for (const Mode& mode : m.modes) {
    modes.push_back({{"kind", ToString(mode.kind)},
                     {"frequency_hz", mode.frequency_hz},
                     {"damping_ratio", mode.damping_ratio}});
  }
  return {{"modes", modes},
          {"mass_kg", m.mass_kg},
          {"stiffness", m.stiffness},
          {"source", ToString(m.source)}};
}

Material ReadMaterial(const JsonReader& r, const nlohmann::json& j, const std::string& at) {
  Material m;
  const auto& modes = r.Array(r.Field(j, "modes", at), Member(at, "modes"));
  if (modes.size() != 3) {
    r.Fail(Member(at, "modes"),
           fmt::format("expected 3 modes (bend_u, bend_w, twist_v), got {}", modes.size()));
  }
  for (size_t i = 0; i < 3; ++i) {
    const std::string mat = Element(Member(at, "modes"), i);
    m.modes[i].kind = ParseModeKind(r.String(r.Field(modes[i], "kind", mat), Member(mat, "kind")),
                                    r.source(), Member(mat, "kind"));
    m.modes[i].frequency_hz =
        r.Number(r.Field(modes[i], "frequency_hz", mat), Member(mat, "frequency_hz"));
    m.modes[i].damping_ratio =
        r.Number(r.Field(modes[i], "damping_ratio", mat), Member(mat, "damping_ratio"));
  }
  m.mass_kg = r.Number(r.Field(j, "mass_kg", at), Member(at, "mass_kg"));
  m.stiffness = r.Number(r.Field(j, "stiffness", at), Member(at, "stiffness"));
  m.source = ParseMaterialSource(r.String(r.Field(j, "source", at), Member(at, "source")),
                                 r.source(), Member(at, "source"));
  return m;
}

Branch ReadBranch(const JsonReader& r, const nlohmann::json& j, const std::string& at,
                  bool* has_frame) {
  Branch b;
  b.id = r.Integer(r.Field(j, "id", at), Member(at, "id"));
  b.parent = r.Integer(r.Field(j, "parent", at), Member(at, "parent"));
  b.parent_node = r.Integer(r.Field(j, "parent_node", at), Member(at, "parent_node"));
  b.level = r.Integer(r.Field(j, "level", at), Member(at, "level"));
  const std::string nat = Member(at, "nodes");
  const auto& nodes = r.Array(r.Field(j, "nodes", at), nat);
  b.nodes.reserve(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const std::string eat = Element(nat, i);
    if (!nodes[i].is_array() || nodes[i].size() != 4) {
      r.Fail(eat, fmt::format("expected 4 numbers [x, y, z, radius], got {}", nodes[i].dump()));
    }
    Node n;
    n.position = {r.Number(nodes[i][0], Element(eat, 0)), r.Number(nodes[i][1], Element(eat, 1)),
                  r.Number(nodes[i][2], Element(eat, 2))};
    n.radius = r.Number(nodes[i][3], Element(eat, 3));
    b.nodes.push_back(n);
  }
  *has_frame = r.Has(j, "frame");
  if (*has_frame) {
    const std::string fat = Member(at, "frame");
    const auto& f = r.Field(j, "frame", at);
    b.frame.u = r.Vector3(r.Field(f, "u", fat), Member(fat, "u"));
    b.frame.v = r.Vector3(r.Field(f, "v", fat), Member(fat, "v"));
    b.frame.w = r.Vector3(r.Field(f, "w", fat), Member(fat, "w"));
  }
  if (r.Has(j, "material") && !j["material"].is_null()) {
    b.material = ReadMaterial(r, j["material"], Member(at, "material"));
  }
  return b;
}

}  // namespace

ModeKind ParseModeKind(const std::string& name, const std::string& source, const std::string& at) {
  for (ModeKind k : {ModeKind::kBendU, ModeKind::kBendW, ModeKind::kTwistV}) {
    if (name == ToString(k)) return k;
  }
  throw InputError(source, at,
                   fmt::format("expected \"bend_u\", \"bend_w\" or \"twist_v\", got \"{}\"", name));
}

MaterialSource ParseMaterialSource(const std::string& name, const std::string& source,
                                   const std::string& at) {
  for (MaterialSource s :
       {MaterialSource::kMeasured, MaterialSource::kInterpolated, MaterialSource::kDefault}) {
    if (name == ToString(s)) return s;
  }
  throw InputError(
      source, at,
      fmt::format("expected \"measured\", \"interpolated\" or \"default\", got \"{}\"", name));
}

Tree TreeFromJson(const nlohmann::json& doc, const std::string& source,
                  const ValidationOptions& validation) {
  JsonReader r(source);
  r.Object(doc, "");
  const std::string format = r.String(r.Field(doc, "format", ""), "format");
  if (format != kTreeFormat) {
    r.Fail("format", fmt::format("expected \"{}\", got \"{}\"", kTreeFormat, format));
  }
  const int version = r.Integer(r.Field(doc, "version", ""), "version");
  if (version != kTreeFormatVersion) {
    r.Fail("version", fmt::format("expected {} (this simtree reads version {}), got {}",
                                  kTreeFormatVersion, kTreeFormatVersion, version));
  }
  Tree tree;
  if (r.Has(doc, "metadata")) {
    const auto& meta = r.Object(doc["metadata"], "metadata");
    if (r.Has(meta, "species"))
      tree.metadata.species = r.String(meta["species"], "metadata.species");
    if (r.Has(meta, "source")) tree.metadata.source = r.String(meta["source"], "metadata.source");
    if (r.Has(meta, "units")) {
      tree.metadata.units = r.String(meta["units"], "metadata.units");
      if (tree.metadata.units != "m") {
        r.Fail("metadata.units",
               fmt::format("expected \"m\" (simtree files are in metres), got \"{}\"",
                           tree.metadata.units));
      }
    }
  }
  const auto& branches = r.Array(r.Field(doc, "branches", ""), "branches");
  bool all_frames = true;
  for (size_t i = 0; i < branches.size(); ++i) {
    bool has_frame = false;
    tree.branches.push_back(ReadBranch(r, branches[i], Element("branches", i), &has_frame));
    all_frames = all_frames && has_frame;
  }
  if (r.Has(doc, "markers")) {
    const auto& markers = r.Array(doc["markers"], "markers");
    for (size_t i = 0; i < markers.size(); ++i) {
      const std::string at = Element("markers", i);
      Marker m;
      m.id = r.Integer(r.Field(markers[i], "id", at), Member(at, "id"));
      if (r.Has(markers[i], "label")) m.label = r.String(markers[i]["label"], Member(at, "label"));
      m.branch = r.Integer(r.Field(markers[i], "branch", at), Member(at, "branch"));
      m.arc_length = r.Number(r.Field(markers[i], "arc_length", at), Member(at, "arc_length"));
      if (r.Has(markers[i], "parent"))
        m.parent = r.Integer(markers[i]["parent"], Member(at, "parent"));
      m.position = r.Vector3(r.Field(markers[i], "position", at), Member(at, "position"));
      tree.markers.push_back(m);
    }
  }
  // Frames are derived data: fill them in when the file leaves them out, and only when the
  // hierarchy is sound enough to derive them from.
  if (!all_frames && FindProblems(tree, validation).empty()) ComputeFrames(tree);
  Validate(tree, source, validation);
  return tree;
}

nlohmann::ordered_json TreeToJson(const Tree& tree) {
  ojson doc;
  doc["format"] = kTreeFormat;
  doc["version"] = kTreeFormatVersion;
  doc["metadata"] = {{"species", tree.metadata.species},
                     {"source", tree.metadata.source},
                     {"units", tree.metadata.units}};
  ojson branches = ojson::array();
  for (const Branch& b : tree.branches) {
    ojson nodes = ojson::array();
    for (const Node& n : b.nodes) {
      nodes.push_back(ojson::array({n.position.x(), n.position.y(), n.position.z(), n.radius}));
    }
    ojson jb = {{"id", b.id},
                {"parent", b.parent},
                {"parent_node", b.parent_node},
                {"level", b.level},
                {"nodes", nodes},
                {"frame",
                 {{"u", VectorJson(b.frame.u)},
                  {"v", VectorJson(b.frame.v)},
                  {"w", VectorJson(b.frame.w)}}}};
    if (b.material) jb["material"] = MaterialJson(*b.material);
    branches.push_back(std::move(jb));
  }
  doc["branches"] = std::move(branches);
  ojson markers = ojson::array();
  for (const Marker& m : tree.markers) {
    markers.push_back({{"id", m.id},
                       {"label", m.label},
                       {"branch", m.branch},
                       {"arc_length", m.arc_length},
                       {"parent", m.parent},
                       {"position", VectorJson(m.position)}});
  }
  doc["markers"] = std::move(markers);
  return doc;
}

Tree ReadTreeJson(const std::filesystem::path& path, const ValidationOptions& validation) {
  const std::string text = ReadFile(path);
  return TreeFromJson(ParseJson(text, path.string()), path.string(), validation);
}

void WriteTreeJson(const Tree& tree, const std::filesystem::path& path) {
  Validate(tree, path.string());
  WriteFileAtomically(path, TreeToJson(tree).dump(1) + "\n");
}

}  // namespace simtree
