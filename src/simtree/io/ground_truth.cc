#include "simtree/io/ground_truth.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/units.h"

namespace fs = std::filesystem;

namespace simtree {
namespace {

using ojson = nlohmann::ordered_json;

constexpr const char* kMarkers2dFormat = "simtree.markers_2d";
constexpr const char* kModalFormat = "simtree.modal_truth";
constexpr const char* kPullLoadFormat = "simtree.pull_load";

std::string Dump(const ojson& doc) { return doc.dump(1) + "\n"; }

nlohmann::json ReadDocument(const fs::path& path) {
  if (!fs::is_regular_file(path)) throw InputError(path.string(), "", "missing (ground truth)");
  return ParseJson(ReadFile(path), path.string());
}

ojson Vec(const Eigen::Vector3d& v) { return ojson::array({v.x(), v.y(), v.z()}); }

void CheckFormat(const JsonReader& r, const nlohmann::json& doc, const char* format) {
  const std::string got = r.String(r.Field(doc, "format", ""), "format");
  if (got != format) r.Fail("format", fmt::format("expected \"{}\", got \"{}\"", format, got));
  const int version = r.Integer(r.Field(doc, "version", ""), "version");
  if (version != 1) r.Fail("version", fmt::format("expected 1, got {}", version));
}

}  // namespace

Eigen::Isometry3d PoseFromJson(const nlohmann::json& value, const std::string& source,
                               const std::string& at) {
  const JsonReader r(source);
  if (!value.is_array() || value.size() != 16) {
    r.Fail(at, fmt::format("expected 16 numbers (a row-major 4x4 matrix), got {}",
                           value.is_array() ? std::to_string(value.size()) + " values"
                                            : std::string(value.type_name())));
  }
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = r.Number(value[i], Element(at, i));
  if (m.row(3).transpose() != Eigen::Vector4d(0, 0, 0, 1)) {
    r.Fail(at, "expected the last row 0 0 0 1 (a rigid transform)");
  }
  const Eigen::Matrix3d rot = m.topLeftCorner<3, 3>();
  if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
      rot.determinant() < 0) {
    r.Fail(at, "expected a rotation (orthonormal, determinant +1) in the upper-left 3x3");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rot;
  pose.translation() = m.topRightCorner<3, 1>();
  return pose;
}

ojson PoseToJson(const Eigen::Isometry3d& pose) {
  ojson out = ojson::array();
  const Eigen::Matrix4d m = pose.matrix();
  for (int i = 0; i < 16; ++i) out.push_back(m(i / 4, i % 4));
  return out;
}

std::vector<ViewPose> ReadScanPoses(const fs::path& path) {
  const nlohmann::json doc = ReadDocument(path);
  const JsonReader r(path.string());
  const auto& views = r.Array(r.Field(doc, "views", ""), "views");
  std::vector<ViewPose> poses;
  for (size_t i = 0; i < views.size(); ++i) {
    const std::string at = Element("views", i);
    ViewPose p;
    p.name = r.String(r.Field(views[i], "name", at), Member(at, "name"));
    p.world_from_camera = PoseFromJson(r.Field(views[i], "world_from_camera", at), path.string(),
                                       Member(at, "world_from_camera"));
    poses.push_back(p);
  }
  return poses;
}

void WriteScanPoses(const std::vector<ViewPose>& poses, const fs::path& path) {
  ojson views = ojson::array();
  for (const ViewPose& p : poses) {
    views.push_back({{"name", p.name}, {"world_from_camera", PoseToJson(p.world_from_camera)}});
  }
  WriteFileAtomically(path, Dump({{"views", views}}));
}

Eigen::Isometry3d ReadPullCamera(const fs::path& path) {
  const nlohmann::json doc = ReadDocument(path);
  const JsonReader r(path.string());
  return PoseFromJson(r.Field(doc, "world_from_camera", ""), path.string(), "world_from_camera");
}

void WritePullCamera(const Eigen::Isometry3d& world_from_camera, const fs::path& path) {
  WriteFileAtomically(path, Dump({{"world_from_camera", PoseToJson(world_from_camera)}}));
}

double PullLoad::ForceAt(double t) const {
  if (t < ramp_start_s || t >= release_s) return 0.0;
  if (t >= hold_start_s || hold_start_s <= ramp_start_s) return force_n;
  // A smooth (cosine) ramp: a person pulling a rope does not jerk it.
  const double s = (t - ramp_start_s) / (hold_start_s - ramp_start_s);
  return force_n * 0.5 * (1.0 - std::cos(kPi * s));
}

PullLoad ReadPullLoad(const fs::path& path) {
  const nlohmann::json doc = ReadDocument(path);
  const JsonReader r(path.string());
  CheckFormat(r, doc, kPullLoadFormat);
  PullLoad l;
  l.branch = r.Integer(r.Field(doc, "branch", ""), "branch");
  l.arc_length = r.Number(r.Field(doc, "arc_length", ""), "arc_length");
  l.attach_point = r.Vector3(r.Field(doc, "attach_point", ""), "attach_point");
  l.anchor = r.Vector3(r.Field(doc, "anchor", ""), "anchor");
  l.force_n = r.Number(r.Field(doc, "force_n", ""), "force_n");
  l.ramp_start_s = r.Number(r.Field(doc, "ramp_start_s", ""), "ramp_start_s");
  l.hold_start_s = r.Number(r.Field(doc, "hold_start_s", ""), "hold_start_s");
  l.release_s = r.Number(r.Field(doc, "release_s", ""), "release_s");
  l.duration_s = r.Number(r.Field(doc, "duration_s", ""), "duration_s");
  if (!(l.ramp_start_s <= l.hold_start_s && l.hold_start_s <= l.release_s)) {
    r.Fail("release_s", "expected ramp_start_s <= hold_start_s <= release_s");
  }
  return l;
}

void WritePullLoad(const PullLoad& l, const fs::path& path) {
  const ojson doc = {{"format", kPullLoadFormat},
                     {"version", 1},
                     {"branch", l.branch},
                     {"arc_length", l.arc_length},
                     {"attach_point", Vec(l.attach_point)},
                     {"anchor", Vec(l.anchor)},
                     {"force_n", l.force_n},
                     {"ramp_start_s", l.ramp_start_s},
                     {"hold_start_s", l.hold_start_s},
                     {"release_s", l.release_s},
                     {"duration_s", l.duration_s}};
  WriteFileAtomically(path, Dump(doc));
}

std::vector<MarkerFrame2d> ReadMarkers2d(const fs::path& path) {
  const nlohmann::json doc = ReadDocument(path);
  const JsonReader r(path.string());
  CheckFormat(r, doc, kMarkers2dFormat);
  const auto& frames = r.Array(r.Field(doc, "frames", ""), "frames");
  std::vector<MarkerFrame2d> out;
  out.reserve(frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string at = Element("frames", i);
    MarkerFrame2d f;
    f.frame = r.Integer(r.Field(frames[i], "frame", at), Member(at, "frame"));
    f.time_s = r.Number(r.Field(frames[i], "time_s", at), Member(at, "time_s"));
    const std::string mat = Member(at, "markers");
    const auto& markers = r.Array(r.Field(frames[i], "markers", at), mat);
    for (size_t k = 0; k < markers.size(); ++k) {
      const std::string kat = Element(mat, k);
      MarkerBox2d m;
      m.id = r.Integer(r.Field(markers[k], "id", kat), Member(kat, "id"));
      const auto& visible = r.Field(markers[k], "visible", kat);
      if (!visible.is_boolean()) r.Fail(Member(kat, "visible"), "expected true or false");
      m.visible = visible.get<bool>();
      m.visible_fraction =
          r.Number(r.Field(markers[k], "visible_fraction", kat), Member(kat, "visible_fraction"));
      m.visible_pixels =
          r.Integer(r.Field(markers[k], "visible_pixels", kat), Member(kat, "visible_pixels"));
      const auto& box = r.Array(r.Field(markers[k], "box", kat), Member(kat, "box"));
      if (box.size() != 4) r.Fail(Member(kat, "box"), "expected [x, y, w, h]");
      for (int c = 0; c < 4; ++c) m.box[c] = r.Number(box[c], Element(Member(kat, "box"), c));
      f.markers.push_back(m);
    }
    out.push_back(std::move(f));
  }
  return out;
}

void WriteMarkers2d(const std::vector<MarkerFrame2d>& frames, const fs::path& path) {
  // Written by hand, one line per frame: the file has hundreds of frames and is meant to be
  // diffed and grepped.
  std::string out =
      fmt::format("{{\"format\": \"{}\", \"version\": 1, \"frames\": [\n", kMarkers2dFormat);
  for (size_t i = 0; i < frames.size(); ++i) {
    const MarkerFrame2d& f = frames[i];
    out += fmt::format(" {{\"frame\": {}, \"time_s\": {:.6f}, \"markers\": [", f.frame, f.time_s);
    for (size_t k = 0; k < f.markers.size(); ++k) {
      const MarkerBox2d& m = f.markers[k];
      out += fmt::format(
          "{}{{\"id\": {}, \"visible\": {}, \"visible_fraction\": {:.3f}, \"visible_pixels\": {}, "
          "\"box\": [{:.2f}, {:.2f}, {:.2f}, {:.2f}]}}",
          k == 0 ? "" : ", ", m.id, m.visible ? "true" : "false", m.visible_fraction,
          m.visible_pixels, m.box[0], m.box[1], m.box[2], m.box[3]);
    }
    out += i + 1 < frames.size() ? "]},\n" : "]}\n";
  }
  out += "]}\n";
  WriteFileAtomically(path, out);
}

namespace {

// The optional "peaks" of a link or branch.
std::vector<ModalTruth::ModePeak> ReadPeaks(const JsonReader& r, const nlohmann::json& owner,
                                            const std::string& at) {
  std::vector<ModalTruth::ModePeak> peaks;
  if (!owner.contains("peaks")) return peaks;
  const std::string pat = Member(at, "peaks");
  const auto& list = r.Array(owner["peaks"], pat);
  for (size_t k = 0; k < list.size(); ++k) {
    const std::string kat = Element(pat, k);
    ModalTruth::ModePeak p;
    p.mode = r.Integer(r.Field(list[k], "mode", kat), Member(kat, "mode"));
    p.frequency_hz = r.Number(r.Field(list[k], "frequency_hz", kat), Member(kat, "frequency_hz"));
    p.damping_ratio =
        r.Number(r.Field(list[k], "damping_ratio", kat), Member(kat, "damping_ratio"));
    p.amplitude = r.Number(r.Field(list[k], "amplitude", kat), Member(kat, "amplitude"));
    p.strength = r.Number(r.Field(list[k], "strength", kat), Member(kat, "strength"));
    peaks.push_back(p);
  }
  return peaks;
}

void WritePeaks(const std::vector<ModalTruth::ModePeak>& peaks, ojson& owner) {
  if (peaks.empty()) return;
  ojson list = ojson::array();
  for (const auto& p : peaks) {
    list.push_back({{"mode", p.mode},
                    {"frequency_hz", p.frequency_hz},
                    {"damping_ratio", p.damping_ratio},
                    {"amplitude", p.amplitude},
                    {"strength", p.strength}});
  }
  owner["peaks"] = std::move(list);
}

}  // namespace

ModalTruth ReadModalTruth(const fs::path& path) {
  const nlohmann::json doc = ReadDocument(path);
  const JsonReader r(path.string());
  CheckFormat(r, doc, kModalFormat);
  ModalTruth t;
  t.source = r.String(r.Field(doc, "source", ""), "source");
  const auto& modes = r.Array(r.Field(doc, "modes", ""), "modes");
  for (size_t i = 0; i < modes.size(); ++i) {
    const std::string at = Element("modes", i);
    ModalTruth::TreeMode m;
    m.frequency_hz = r.Number(r.Field(modes[i], "frequency_hz", at), Member(at, "frequency_hz"));
    m.damping_ratio = r.Number(r.Field(modes[i], "damping_ratio", at), Member(at, "damping_ratio"));
    // Optional: files before the effective masses have neither.
    const auto optional = [&](const char* key, std::optional<double>& field) {
      if (r.Has(modes[i], key)) field = r.Number(modes[i][key], Member(at, key));
    };
    optional("horizontal_mass_fraction", m.horizontal_mass_fraction);
    optional("torsion_mass_fraction", m.torsion_mass_fraction);
    t.modes.push_back(m);
  }
  if (r.Has(doc, "lowest_sway_mode")) {
    const int mode = r.Integer(doc["lowest_sway_mode"], "lowest_sway_mode");
    if (mode < 0 || mode >= static_cast<int>(t.modes.size())) {
      r.Fail("lowest_sway_mode", fmt::format("expected an index into modes (0-{}), got {}",
                                             static_cast<int>(t.modes.size()) - 1, mode));
    }
    t.lowest_sway_mode = mode;
  }
  const auto& links = r.Array(r.Field(doc, "links", ""), "links");
  for (size_t i = 0; i < links.size(); ++i) {
    const std::string at = Element("links", i);
    ModalTruth::Link l;
    l.parent = r.Integer(r.Field(links[i], "parent", at), Member(at, "parent"));
    l.child = r.Integer(r.Field(links[i], "child", at), Member(at, "child"));
    l.frequency_hz = r.Number(r.Field(links[i], "frequency_hz", at), Member(at, "frequency_hz"));
    l.damping_ratio = r.Number(r.Field(links[i], "damping_ratio", at), Member(at, "damping_ratio"));
    l.peaks = ReadPeaks(r, links[i], at);
    t.links.push_back(l);
  }
  const auto& branches = r.Array(r.Field(doc, "branches", ""), "branches");
  for (size_t i = 0; i < branches.size(); ++i) {
    const std::string at = Element("branches", i);
    ModalTruth::BranchTruth b;
    b.branch = r.Integer(r.Field(branches[i], "branch", at), Member(at, "branch"));
    b.frequency_hz = r.Number(r.Field(branches[i], "frequency_hz", at), Member(at, "frequency_hz"));
    b.damping_ratio =
        r.Number(r.Field(branches[i], "damping_ratio", at), Member(at, "damping_ratio"));
    b.peaks = ReadPeaks(r, branches[i], at);
    t.branches.push_back(b);
  }
  return t;
}

void WriteModalTruth(const ModalTruth& t, const fs::path& path) {
  ojson modes = ojson::array(), links = ojson::array(), branches = ojson::array();
  for (const auto& m : t.modes) {
    ojson mode = {{"frequency_hz", m.frequency_hz}, {"damping_ratio", m.damping_ratio}};
    if (m.horizontal_mass_fraction) mode["horizontal_mass_fraction"] = *m.horizontal_mass_fraction;
    if (m.torsion_mass_fraction) mode["torsion_mass_fraction"] = *m.torsion_mass_fraction;
    modes.push_back(std::move(mode));
  }
  for (const auto& l : t.links) {
    ojson link = {{"parent", l.parent},
                  {"child", l.child},
                  {"frequency_hz", l.frequency_hz},
                  {"damping_ratio", l.damping_ratio}};
    WritePeaks(l.peaks, link);
    links.push_back(std::move(link));
  }
  for (const auto& b : t.branches) {
    ojson branch = {
        {"branch", b.branch}, {"frequency_hz", b.frequency_hz}, {"damping_ratio", b.damping_ratio}};
    WritePeaks(b.peaks, branch);
    branches.push_back(std::move(branch));
  }
  ojson doc = {{"format", kModalFormat}, {"version", 1}, {"source", t.source}, {"modes", modes}};
  if (t.lowest_sway_mode) doc["lowest_sway_mode"] = *t.lowest_sway_mode;
  doc["links"] = std::move(links);
  doc["branches"] = std::move(branches);
  WriteFileAtomically(path, Dump(doc));
}

}  // namespace simtree
