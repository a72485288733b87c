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

JsonDocument ReadDocument(const fs::path& path) {
  if (!fs::is_regular_file(path)) throw InputError(path.string(), "", "missing (ground truth)");
  return ReadJsonDocument(path);
}

ojson Vec(const Eigen::Vector3d& v) { return ojson::array({v.x(), v.y(), v.z()}); }

}  // namespace

Eigen::Isometry3d PoseFromJson(const JsonNode& value) {
  if (!value.json().is_array() || value.json().size() != 16) {
    value.Fail(fmt::format("expected 16 numbers (a row-major 4x4 matrix), got {}",
                           value.json().is_array() ? std::to_string(value.size()) + " values"
                                                   : std::string(value.json().type_name())));
  }
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = value.Item(i).Number();
  if (m.row(3).transpose() != Eigen::Vector4d(0, 0, 0, 1)) {
    value.Fail("expected the last row 0 0 0 1 (a rigid transform)");
  }
  const Eigen::Matrix3d rot = m.topLeftCorner<3, 3>();
  if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
      rot.determinant() < 0) {
    value.Fail("expected a rotation (orthonormal, determinant +1) in the upper-left 3x3");
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
  const JsonDocument file = ReadDocument(path);
  std::vector<ViewPose> poses;
  for (const JsonNode& view : file.root().Field("views").Items()) {
    ViewPose p;
    p.name = view.String("name");
    p.world_from_camera = PoseFromJson(view.Field("world_from_camera"));
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
  const JsonDocument file = ReadDocument(path);
  return PoseFromJson(file.root().Field("world_from_camera"));
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
  const JsonDocument file = ReadDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kPullLoadFormat, 1);
  PullLoad l;
  l.branch = doc.Integer("branch");
  l.arc_length = doc.Number("arc_length");
  l.attach_point = doc.Vector3("attach_point");
  l.anchor = doc.Vector3("anchor");
  l.force_n = doc.Number("force_n");
  l.ramp_start_s = doc.Number("ramp_start_s");
  l.hold_start_s = doc.Number("hold_start_s");
  l.release_s = doc.Number("release_s");
  l.duration_s = doc.Number("duration_s");
  if (!(l.ramp_start_s <= l.hold_start_s && l.hold_start_s <= l.release_s)) {
    doc.FailAt("release_s", "expected ramp_start_s <= hold_start_s <= release_s");
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
  const JsonDocument file = ReadDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kMarkers2dFormat, 1);
  const JsonNode frames = doc.Field("frames");
  std::vector<MarkerFrame2d> out;
  out.reserve(frames.size());
  for (const JsonNode& frame : frames.Items()) {
    MarkerFrame2d f;
    f.frame = frame.Integer("frame");
    f.time_s = frame.Number("time_s");
    for (const JsonNode& marker : frame.Field("markers").Items()) {
      MarkerBox2d m;
      m.id = marker.Integer("id");
      m.visible = marker.Bool("visible");
      m.visible_fraction = marker.Number("visible_fraction");
      m.visible_pixels = marker.Integer("visible_pixels");
      const JsonNode box = marker.Field("box");
      if (box.size() != 4) box.Fail("expected [x, y, w, h]");
      for (int c = 0; c < 4; ++c) m.box[c] = box.Item(c).Number();
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
std::vector<ModalTruth::ModePeak> ReadPeaks(const JsonNode& owner) {
  std::vector<ModalTruth::ModePeak> peaks;
  const auto list = owner.Find("peaks");
  if (!list) return peaks;
  for (const JsonNode& peak : list->Items()) {
    ModalTruth::ModePeak p;
    p.mode = peak.Integer("mode");
    p.frequency_hz = peak.Number("frequency_hz");
    p.damping_ratio = peak.Number("damping_ratio");
    p.amplitude = peak.Number("amplitude");
    p.strength = peak.Number("strength");
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
  const JsonDocument file = ReadDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kModalFormat, 1);
  ModalTruth t;
  t.source = doc.String("source");
  for (const JsonNode& mode : doc.Field("modes").Items()) {
    ModalTruth::TreeMode m;
    m.frequency_hz = mode.Number("frequency_hz");
    m.damping_ratio = mode.Number("damping_ratio");
    // Optional: files before the effective masses have neither.
    if (const auto f = mode.Find("horizontal_mass_fraction"))
      m.horizontal_mass_fraction = f->Number();
    if (const auto f = mode.Find("torsion_mass_fraction")) m.torsion_mass_fraction = f->Number();
    t.modes.push_back(m);
  }
  if (const auto lowest = doc.Find("lowest_sway_mode")) {
    const int mode = lowest->Integer();
    if (mode < 0 || mode >= static_cast<int>(t.modes.size())) {
      lowest->Fail(fmt::format("expected an index into modes (0-{}), got {}",
                               static_cast<int>(t.modes.size()) - 1, mode));
    }
    t.lowest_sway_mode = mode;
  }
  for (const JsonNode& link : doc.Field("links").Items()) {
    ModalTruth::Link l;
    l.parent = link.Integer("parent");
    l.child = link.Integer("child");
    l.frequency_hz = link.Number("frequency_hz");
    l.damping_ratio = link.Number("damping_ratio");
    l.peaks = ReadPeaks(link);
    t.links.push_back(l);
  }
  for (const JsonNode& branch : doc.Field("branches").Items()) {
    ModalTruth::BranchTruth b;
    b.branch = branch.Integer("branch");
    b.frequency_hz = branch.Number("frequency_hz");
    b.damping_ratio = branch.Number("damping_ratio");
    b.peaks = ReadPeaks(branch);
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
