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
  ojson out = {{"modes", modes},
               {"mass_kg", m.mass_kg},
               {"stiffness", m.stiffness},
               {"source", ToString(m.source)}};
  if (!m.uncertain.empty()) out["uncertain"] = m.uncertain;  // absent: not flagged (older files)
  return out;
}

Material ReadMaterial(const JsonNode& j) {
  Material m;
  const JsonNode modes = j.Field("modes");
  if (modes.size() != 3) {
    modes.Fail(fmt::format("expected 3 modes (bend_u, bend_w, twist_v), got {}", modes.size()));
  }
  for (size_t i = 0; i < 3; ++i) {
    const JsonNode mode = modes.Item(i);
    const JsonNode kind = mode.Field("kind");
    m.modes[i].kind = ParseModeKind(kind.String(), kind.source(), kind.at());
    m.modes[i].frequency_hz = mode.Number("frequency_hz");
    m.modes[i].damping_ratio = mode.Number("damping_ratio");
  }
  m.mass_kg = j.Number("mass_kg");
  m.stiffness = j.Number("stiffness");
  const JsonNode source = j.Field("source");
  m.source = ParseMaterialSource(source.String(), source.source(), source.at());
  if (j.Has("uncertain")) m.uncertain = j.String("uncertain");
  return m;
}

Branch ReadBranch(const JsonNode& j, bool* has_frame) {
  Branch b;
  b.id = j.Integer("id");
  b.parent = j.Integer("parent");
  b.parent_node = j.Integer("parent_node");
  b.level = j.Integer("level");
  const JsonNode nodes = j.Field("nodes");
  b.nodes.reserve(nodes.size());
  for (const JsonNode& node : nodes.Items()) {
    if (!node.json().is_array() || node.json().size() != 4) {
      node.Fail(fmt::format("expected 4 numbers [x, y, z, radius], got {}", node.json().dump()));
    }
    Node n;
    n.position = {node.Item(0).Number(), node.Item(1).Number(), node.Item(2).Number()};
    n.radius = node.Item(3).Number();
    b.nodes.push_back(n);
  }
  *has_frame = j.Has("frame");
  if (*has_frame) {
    const JsonNode frame = j.Field("frame");
    b.frame.u = frame.Vector3("u");
    b.frame.v = frame.Vector3("v");
    b.frame.w = frame.Vector3("w");
  }
  if (const auto material = j.Find("material"); material && !material->is_null()) {
    b.material = ReadMaterial(*material);
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
  for (MaterialSource s : {MaterialSource::kMeasured, MaterialSource::kInterpolated,
                           MaterialSource::kDefault, MaterialSource::kAssumed}) {
    if (name == ToString(s)) return s;
  }
  throw InputError(source, at,
                   fmt::format("expected \"measured\", \"interpolated\", \"default\" or "
                               "\"assumed\", got \"{}\"",
                               name));
}

Tree TreeFromJson(const nlohmann::json& value, const std::string& source,
                  const ValidationOptions& validation) {
  const JsonNode doc(value, source);
  CheckFormat(doc, kTreeFormat, kTreeFormatVersion);
  Tree tree;
  if (const auto meta = doc.Find("metadata")) {
    meta->ExpectObject();
    if (const auto species = meta->Find("species")) tree.metadata.species = species->String();
    if (const auto from = meta->Find("source")) tree.metadata.source = from->String();
    if (const auto units = meta->Find("units")) {
      tree.metadata.units = units->String();
      if (tree.metadata.units != "m") {
        units->Fail(fmt::format("expected \"m\" (simtree files are in metres), got \"{}\"",
                                tree.metadata.units));
      }
    }
  }
  bool all_frames = true;
  for (const JsonNode& branch : doc.Field("branches").Items()) {
    bool has_frame = false;
    tree.branches.push_back(ReadBranch(branch, &has_frame));
    all_frames = all_frames && has_frame;
  }
  if (const auto markers = doc.Find("markers")) {
    for (const JsonNode& j : markers->Items()) {
      Marker m;
      m.id = j.Integer("id");
      if (const auto label = j.Find("label")) m.label = label->String();
      m.branch = j.Integer("branch");
      m.arc_length = j.Number("arc_length");
      if (const auto parent = j.Find("parent")) m.parent = parent->Integer();
      m.position = j.Vector3("position");
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
