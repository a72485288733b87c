// Writes the seed corpora of the fuzz targets with simtree's own writers (and the shared data's
// real files where they are small), so the seeds are what simtree and the cameras actually make:
//   simtree_fuzz_seeds <out> [<shared data folder>]  ->  <out>/<target>/<seed files>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <open3d/io/PointCloudIO.h>

#include "core/tree_fixtures.h"  // the core tests' small trees
#include "simtree/core/atomic_file.h"
#include "simtree/core/legacy_format.h"
#include "simtree/core/tree_json.h"
#include "simtree/identification/detail/test_signals.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/azure_kinect.h"
#include "simtree/io/capture.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/io/track_init.h"
#include "simtree/io/trajectories.h"
#include "support/las_writer.h"
#include "support/open3d_folder_writer.h"
#include "support/ros_bag_writer.h"
#include "support/tum_rgbd_writer.h"

namespace fs = std::filesystem;

namespace simtree::fuzz {
namespace {

fs::path Target(const fs::path& out, const std::string& name) {
  fs::create_directories(out / name);
  return out / name;
}

void CopyIfPresent(const fs::path& from, const fs::path& to) {
  if (fs::exists(from)) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

void TreeSeeds(const fs::path& out, const fs::path& shared) {
  WriteTreeJson(test::SmallTreeWithMaterials(), Target(out, "tree_json") / "simready.json");
  WriteTreeJson(test::SmallTree(), Target(out, "tree_json") / "static.json");
  WriteLegacyTree(test::SmallTree(), Target(out, "legacy_tree") / "small.txt");
  CopyIfPresent(shared / "authors-demo/tree_model/tree01.txt", out / "legacy_tree/tree01.txt");
  // Four branches, as the fuzz target's fixed tree.
  WriteLegacyParameters(test::SmallTreeWithMaterials(),
                        Target(out, "legacy_parameters") / "tree_parameters.txt");
  CopyIfPresent(shared / "authors-demo/tree_parameters.txt", out / "legacy_parameters/authors.txt");
}

// A pull test of three linked markers (as the materials tests make it) gives markers.json and
// trajectories.csv; materials.json holds a measured link, a missing one and the branch modes
// (identifying the record itself takes minutes under the sanitizers).
void PullTestSeeds(const fs::path& out) {
  identification::SyntheticMarkerTree tree;
  tree.links.resize(2);
  tree.links[0].theta_u = {{1.2, 0.03, 0.1, 0.0}};
  tree.links[0].theta_w = {{1.4, 0.04, 0.06, 0.0}};
  tree.links[1].parent = 0;
  tree.links[1].rest_direction = {1, -0.2, 0};
  tree.links[1].theta_u = {{1.6, 0.05, 0.1, 0.0}};
  std::vector<MarkerLink> markers;
  const Trajectories full = identification::MakeMarkerTrajectories(tree, 30, 0.2, 2, &markers);
  markers[1].branch = 3;
  WriteMarkersJson(markers, Target(out, "markers_json") / "markers.json");
  identification::MaterialsFile materials;
  materials.trajectories = "trajectories.csv";
  materials.frame_rate_hz = 30;
  materials.release_time_s = 0.2;
  materials.release_detected = true;
  materials.window_start_s = 0.3;
  materials.window_end_s = 2.2;
  identification::LinkMaterial measured;
  measured.child = 1;
  measured.parent = 0;
  measured.label = "M1";
  measured.branch = 3;
  measured.value.frequency_hz = 1.2;
  measured.value.damping_ratio = 0.03;
  measured.value.frequency_std_hz = 0.01;
  measured.value.damping_std = 0.004;
  measured.planes = {measured.value, measured.value};
  for (identification::EstimatorKind kind : identification::AllEstimators()) {
    measured.estimators.emplace_back(kind, measured.value);
  }
  identification::LinkMaterial missing;
  missing.child = 2;
  missing.parent = 1;
  missing.label = "M2";
  missing.value.status = identification::EstimateStatus::kMissingMarker;
  materials.links = {measured, missing};
  identification::AssignBranchMaterials(materials);
  identification::WriteMaterialsJson(materials, Target(out, "materials_json") / "materials.json");
  // A second of it, with one marker lost for a frame (an empty, invalid row).
  Trajectories part;
  part.tracks.resize(full.tracks.size());
  for (size_t m = 0; m < full.tracks.size(); ++m) part.tracks[m].marker = full.tracks[m].marker;
  for (int f = 0; f < 30; ++f) {
    std::vector<Eigen::Vector3d> positions;
    std::vector<bool> valid;
    for (const MarkerTrack& track : full.tracks) {
      positions.push_back(track.positions[f]);
      valid.push_back(track.valid[f] && !(f == 5 && track.marker == 1));
    }
    part.AddFrame(full.frames[f], full.times_s[f], positions, valid);
  }
  WriteTrajectoriesCsv(part, Target(out, "trajectories_csv") / "trajectories.csv");
}

void CaptureSeeds(const fs::path& out, const fs::path& shared) {
  const CameraIntrinsics intrinsics{640, 576, 504.2, 504.5, 320.1, 333.7, 0.001};
  WriteIntrinsicsJson(intrinsics, Target(out, "intrinsics_json") / "intrinsics.json");
  const fs::path files = Target(out, "capture_files");
  WriteCaptureInfo({"azure_kinect_nfov_unbinned", "acer_rubrum", "fuzz seed"},
                   files / "capture.json");
  WriteTrackInitJson({0, {{0, {312.4, 401.2}}, {1, {298.0, 250.5}}}}, files / "init.json");
  std::vector<PullFrame> frames;
  for (int f = 0; f < 3; ++f) {
    const std::string name = fmt::format("{:06d}.png", f);
    frames.push_back({f, f / 30.0, "color/" + name, "depth/" + name});
  }
  WriteFramesCsv(frames, files / "frames.csv");
  CopyIfPresent(shared / "azure-kinect/pyk4a_calibration.json",
                Target(out, "azure_calibration") / "calibration.json");
}

void PointCloudSeeds(const fs::path& out) {
  open3d::geometry::PointCloud cloud;
  for (int i = 0; i < 24; ++i) {
    cloud.points_.emplace_back(0.01 * i, 0.02 * (i % 5), 1.0 + 0.03 * (i % 7));
  }
  WritePointCloud(cloud, Target(out, "point_cloud_xyz") / "cloud.xyz");
  WritePointCloud(cloud, Target(out, "point_cloud_ply") / "binary.ply");
  WritePointCloud(cloud, Target(out, "point_cloud_pcd") / "binary.pcd");
  // The other encodings Open3D reads, with normals and colours as a scanner's file has them.
  cloud.EstimateNormals();
  cloud.colors_.assign(cloud.points_.size(), Eigen::Vector3d(0.4, 0.3, 0.2));
  using Option = open3d::io::WritePointCloudOption;
  open3d::io::WritePointCloud((out / "point_cloud_ply/ascii.ply").string(), cloud,
                              Option(Option::IsAscii::Ascii));
  open3d::io::WritePointCloud((out / "point_cloud_pcd/ascii.pcd").string(), cloud,
                              Option(Option::IsAscii::Ascii));
  open3d::io::WritePointCloud((out / "point_cloud_pcd/compressed.pcd").string(), cloud,
                              Option(Option::IsAscii::Binary, Option::Compressed::Compressed));
}

void ImageSeeds(const fs::path& out) {
  DepthImage depth(16, 12);
  RgbImage color(16, 12);
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 16; ++x) {
      depth.at(x, y) = static_cast<uint16_t>(800 + 37 * x + 91 * y);
      for (int c = 0; c < 3; ++c) color.at(x, y, c) = static_cast<uint8_t>(20 * x + 7 * y + 60 * c);
    }
  }
  WritePng(depth, Target(out, "png_image") / "depth.png");
  WritePng(color, out / "png_image/color.png");
}

// Recordings laid out as k4arecorder's, written by simtree's writer (as its tests do), kept
// small: 16:9 colour at 128x72, and one with the smallest depth mode (320x288, binned NFOV).
void RecordingSeeds(const fs::path& out, const fs::path& shared) {
  const fs::path calibration = shared / "azure-kinect/pyk4a_calibration.json";
  if (!fs::exists(calibration)) return;
  for (const bool with_depth : {false, true}) {
    AzureWriterOptions o;
    o.color_width = 128;
    o.color_height = 72;
    o.depth_width = with_depth ? 320 : 0;
    o.depth_height = with_depth ? 288 : 0;
    o.calibration_json = ReadFile(calibration);
    AzureKinectWriter writer(Target(out, "azure_mkv") / (with_depth ? "depth.mkv" : "color.mkv"),
                             o);
    const int count = with_depth ? 1 : 3;
    for (int f = 0; f < count; ++f) {
      AzureCapture c;
      c.color_timestamp_us = c.depth_timestamp_us = 200000 + 33333 * f;
      c.color.emplace(128, 72, static_cast<uint8_t>(40 + 30 * f));
      if (with_depth) c.depth.emplace(320, 288, static_cast<uint16_t>(1500));
      writer.Write(c);
    }
    writer.Close();
  }
}

// The other programs' files, by the readers' tests' writers (tests/support/): LAS in three versions
// (colour, variable length records, extra bytes), a RealSense bag per chunk compression, a TUM
// sequence's two lists (the fuzz target writes the images they name) and Open3D's intrinsic.json.
void RecordingFormatSeeds(const fs::path& out) {
  const std::vector<test::LasPoint> points = {
      {0, 0, 0, 255, 0, 0}, {1500, -2500, 123, 0, 128, 255}, {-40, 70, 9, 3, 4, 5}};
  const fs::path las = Target(out, "point_cloud_las");
  test::WriteLas(las / "v12_f0.las", {}, points);
  test::LasSpec colour;
  colour.minor = 3;
  colour.format = 3;
  colour.vlr_bytes = 54;
  test::WriteLas(las / "v13_f3_vlr.las", colour, points);
  test::LasSpec v14;
  v14.minor = 4;
  v14.format = 7;
  v14.extra_bytes = 3;
  test::WriteLas(las / "v14_f7_extra.las", v14, points);
  for (const std::string compression : {"none", "lz4", "bz2"}) {
    if (!test::BagCompressionWritten(compression)) continue;
    test::BagSpec spec;
    spec.compression = compression;
    test::WriteBag(Target(out, "realsense_bag") / (compression + ".bag"), spec);
  }
  const fs::path tum = test::WriteTumSequence(out / "tum_sequence");
  fs::copy_file(tum / "rgb.txt", Target(out, "tum_list") / "rgb.txt",
                fs::copy_options::overwrite_existing);
  fs::copy_file(tum / "depth.txt", out / "tum_list/depth.txt",
                fs::copy_options::overwrite_existing);
  fs::remove_all(tum);
  WriteFileAtomically(Target(out, "open3d_intrinsic") / "intrinsic.json",
                      test::Open3dIntrinsicJson());
  WriteIntrinsicsJson({40, 30, 35, 36, 19.5, 14.5, 0.001}, out / "open3d_intrinsic/simtree.json");
}

}  // namespace
}  // namespace simtree::fuzz

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s <corpus folder> [<shared data folder>]\n", argv[0]);
    return 2;
  }
  const fs::path out = argv[1];
  const fs::path shared = argc > 2 ? fs::path(argv[2]) : fs::path();
  using namespace simtree::fuzz;
  TreeSeeds(out, shared);
  PullTestSeeds(out);
  CaptureSeeds(out, shared);
  PointCloudSeeds(out);
  ImageSeeds(out);
  RecordingSeeds(out, shared);
  RecordingFormatSeeds(out);
  return 0;
}
