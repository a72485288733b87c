#include "simtree/synth/detail/sensor_scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <embree3/rtcore.h>

#include "simtree/core/error.h"
#include "simtree/core/validate.h"
#include "simtree/synth/detail/sensor_scene_props.h"
#include "simtree/synth/detail/sensor_tree_tubes.h"

namespace simtree::synth {
namespace {

// What an Embree geometry of the scene is.
struct GeometryInfo {
  SurfaceKind kind = SurfaceKind::kNone;
  SceneObject object = SceneObject::kNone;
  int object_index = -1;
  int curves = -1;  // index into Impl::curve_tables for posts, shrubs and the rope
};

// Per segment of a curve geometry that is not the tree: where it starts along its polyline, its
// length, and its end radii (for the hit's `along` and `radius`).
struct CurveTable {
  std::vector<float> along0;
  std::vector<float> length;
  std::vector<float> radius0;
  std::vector<float> radius1;
};

CurveTable MakeCurveTable(const CurveSet& curves) {
  CurveTable table;
  for (uint32_t first : curves.segments) {
    table.along0.push_back(curves.along[first]);
    table.length.push_back(curves.along[first + 1] - curves.along[first]);
    table.radius0.push_back(curves.vertices[first].w());
    table.radius1.push_back(curves.vertices[first + 1].w());
  }
  return table;
}

void InitRay(RTCRay& ray, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
             double t_near, double t_far) {
  ray.org_x = static_cast<float>(origin.x());
  ray.org_y = static_cast<float>(origin.y());
  ray.org_z = static_cast<float>(origin.z());
  ray.dir_x = static_cast<float>(direction.x());
  ray.dir_y = static_cast<float>(direction.y());
  ray.dir_z = static_cast<float>(direction.z());
  ray.tnear = static_cast<float>(t_near);
  ray.tfar =
      std::isfinite(t_far) ? static_cast<float>(t_far) : std::numeric_limits<float>::infinity();
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
}

constexpr size_t kPacket = 16;  // rays per Embree packet

// Lane `i` of a packet of 16 rays; unused lanes repeat a valid ray and are masked out.
void InitRayLane(RTCRay16& rays, size_t i, const Eigen::Vector3d& origin,
                 const Eigen::Vector3d& direction, double t_near, double t_far) {
  rays.org_x[i] = static_cast<float>(origin.x());
  rays.org_y[i] = static_cast<float>(origin.y());
  rays.org_z[i] = static_cast<float>(origin.z());
  rays.dir_x[i] = static_cast<float>(direction.x());
  rays.dir_y[i] = static_cast<float>(direction.y());
  rays.dir_z[i] = static_cast<float>(direction.z());
  rays.tnear[i] = static_cast<float>(t_near);
  rays.tfar[i] =
      std::isfinite(t_far) ? static_cast<float>(t_far) : std::numeric_limits<float>::infinity();
  rays.time[i] = 0.0f;
  rays.mask[i] = 0xFFFFFFFFu;
  rays.id[i] = static_cast<unsigned>(i);
  rays.flags[i] = 0;
}

// The nearest t > 0 at which origin + t direction meets the side of the cone frustum from p0
// (radius r0) to p1 (radius r1), within the frustum's length; nullopt when it does not.
std::optional<double> IntersectFrustum(const Eigen::Vector3d& origin,
                                       const Eigen::Vector3d& direction, const Eigen::Vector3d& p0,
                                       const Eigen::Vector3d& p1, double r0, double r1) {
  const Eigen::Vector3d axis = p1 - p0;
  const double length = axis.norm();
  if (length <= 0.0) return std::nullopt;
  const Eigen::Vector3d a = axis / length;
  const double k = (r1 - r0) / length;  // radius per unit of axial distance
  const Eigen::Vector3d w = origin - p0;
  const double wa = w.dot(a);
  const double da = direction.dot(a);
  const double ra = r0 + k * wa;
  // |w + t d|^2 - ((w + t d).a)^2 = (r0 + k (w + t d).a)^2, a quadratic in t.
  const double qa = direction.squaredNorm() - da * da - k * k * da * da;
  const double qb = 2.0 * (w.dot(direction) - wa * da - k * da * ra);
  const double qc = w.squaredNorm() - wa * wa - ra * ra;
  double roots[2];
  int count = 0;
  if (std::abs(qa) < 1e-14) {
    if (std::abs(qb) < 1e-14) return std::nullopt;
    roots[count++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) return std::nullopt;
    const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
    roots[count++] = q / qa;
    if (q != 0.0) roots[count++] = qc / q;
  }
  std::optional<double> best;
  for (int i = 0; i < count; ++i) {
    const double t = roots[i];
    const double s = wa + t * da;
    if (t <= 0.0 || s < 0.0 || s > length || r0 + k * s < 0.0) continue;
    if (!best || t < *best) best = t;
  }
  return best;
}

void CheckFinite(double value, const std::string& source, const std::string& field) {
  if (!std::isfinite(value)) {
    throw InputError(source, field, "expected a finite number, got " + std::to_string(value));
  }
}

void CheckPositive(double value, const std::string& source, const std::string& field) {
  CheckFinite(value, source, field);
  if (value <= 0.0) {
    throw InputError(source, field, "expected a positive value, got " + std::to_string(value));
  }
}

}  // namespace

const char* ToString(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::kNone:
      return "none";
    case SurfaceKind::kBranch:
      return "branch";
    case SurfaceKind::kGround:
      return "ground";
    case SurfaceKind::kBackground:
      return "background";
    case SurfaceKind::kRope:
      return "rope";
    case SurfaceKind::kOccluder:
      return "occluder";
  }
  return "unknown";
}

void ValidateSceneOptions(const SceneOptions& o, const std::string& source) {
  CheckPositive(o.ground_half_size_m, source, "ground_half_size_m");
  CheckFinite(o.hedge_center.x(), source, "hedge_center.x");
  CheckFinite(o.hedge_center.y(), source, "hedge_center.y");
  CheckPositive(o.hedge_radius_m, source, "hedge_radius_m");
  CheckPositive(o.hedge_height_m, source, "hedge_height_m");
  CheckPositive(o.tape_width_m, source, "tape_width_m");
  CheckPositive(o.rope_radius_m, source, "rope_radius_m");
  CheckPositive(o.tube_tolerance_m, source, "tube_tolerance_m");
  if (!o.sun_direction.allFinite() || o.sun_direction.norm() < 1e-9) {
    throw InputError(source, "sun_direction", "expected a finite, non-zero direction");
  }
  CheckFinite(o.sun_intensity, source, "sun_intensity");
  CheckFinite(o.ambient_intensity, source, "ambient_intensity");
  for (size_t i = 0; i < o.boxes.size(); ++i) {
    const std::string at = "boxes[" + std::to_string(i) + "]";
    if (!o.boxes[i].center.allFinite() || !std::isfinite(o.boxes[i].yaw_rad)) {
      throw InputError(source, at, "expected a finite centre and yaw");
    }
    if (!(o.boxes[i].half_extent.array() > 0.0).all() || !o.boxes[i].half_extent.allFinite()) {
      throw InputError(source, at + ".half_extent", "expected three positive half sizes");
    }
  }
  for (size_t i = 0; i < o.posts.size(); ++i) {
    const std::string at = "posts[" + std::to_string(i) + "]";
    CheckFinite(o.posts[i].base.x(), source, at + ".base.x");
    CheckFinite(o.posts[i].base.y(), source, at + ".base.y");
    CheckPositive(o.posts[i].radius_m, source, at + ".radius_m");
    CheckPositive(o.posts[i].height_m, source, at + ".height_m");
  }
  for (size_t i = 0; i < o.shrubs.size(); ++i) {
    const std::string at = "shrubs[" + std::to_string(i) + "]";
    if (!o.shrubs[i].center.allFinite()) throw InputError(source, at, "expected a finite centre");
    CheckPositive(o.shrubs[i].radius_m, source, at + ".radius_m");
    if (o.shrubs[i].twigs <= 0) throw InputError(source, at + ".twigs", "expected at least 1");
  }
}

SceneOptions DefaultSceneOptions(const Tree& tree, uint64_t seed, bool hard) {
  SceneOptions options;
  options.texture_seed = seed;
  std::mt19937_64 random(seed ^ 0x5CE9E5u);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector2d base = tree.empty()
                                   ? Eigen::Vector2d::Zero()
                                   : Eigen::Vector2d(tree.trunk().base().position.head<2>());
  double crown_radius = 0.0;
  for (const Branch& b : tree.branches) {
    for (const Node& n : b.nodes) {
      crown_radius = std::max(crown_radius, (n.position.head<2>() - base).norm());
    }
  }
  // Cameras stand up to 3 m from the crown; the hedge stays a metre beyond their reach.
  options.hedge_center = base;
  options.hedge_radius_m = std::max(8.0, crown_radius + 3.0 + 3.86 + 1.0);
  // A low winter sun.
  const double sun_azimuth = 2.0 * std::numbers::pi * unit(random);
  const double sun_elevation = (20.0 + 15.0 * unit(random)) * std::numbers::pi / 180.0;
  options.sun_direction =
      Eigen::Vector3d(std::cos(sun_azimuth) * std::cos(sun_elevation),
                      std::sin(sun_azimuth) * std::cos(sun_elevation), std::sin(sun_elevation));
  // Three low objects near the trunk (a stone, a crate, a bin), in range of every camera.
  const Eigen::Vector3f colours[] = {
      {0.52f, 0.52f, 0.50f}, {0.55f, 0.42f, 0.28f}, {0.12f, 0.25f, 0.16f}};
  const double trunk_radius = tree.empty() ? 0.05 : tree.trunk().base().radius;
  for (int i = 0; i < 3; ++i) {
    SceneBox box;
    const double angle = 2.0 * std::numbers::pi * (i + 0.6 * unit(random)) / 3.0;
    const double distance = trunk_radius + 0.7 + 0.7 * unit(random);
    box.half_extent = Eigen::Vector3d(0.12 + 0.12 * unit(random), 0.10 + 0.10 * unit(random),
                                      0.08 + 0.15 * unit(random));
    box.center = Eigen::Vector3d(base.x() + distance * std::cos(angle),
                                 base.y() + distance * std::sin(angle), box.half_extent.z());
    box.yaw_rad = std::numbers::pi * unit(random);
    box.albedo = colours[i];
    options.boxes.push_back(box);
  }
  if (hard) {
    const double post_angle = 2.0 * std::numbers::pi * unit(random);
    const double post_distance = trunk_radius + 1.0 + 0.4 * unit(random);
    options.posts.push_back(ScenePost{
        .base = base + post_distance * Eigen::Vector2d(std::cos(post_angle), std::sin(post_angle)),
        .radius_m = 0.04,
        .height_m = 1.8});
    const double shrub_angle = post_angle + std::numbers::pi * (0.5 + unit(random));
    const double shrub_distance = trunk_radius + 1.3 + 0.5 * unit(random);
    options.shrubs.push_back(SceneShrub{
        .center = Eigen::Vector3d(base.x() + shrub_distance * std::cos(shrub_angle),
                                  base.y() + shrub_distance * std::sin(shrub_angle), 0.35),
        .radius_m = 0.45,
        .twigs = 70,
        .seed = seed + 1});
  }
  return options;
}

struct SensorScene::Impl {
  Tree tree;
  TreePose pose;
  SceneOptions options;
  std::optional<RopeSegment> rope;
  std::vector<MarkerBand> bands;
  std::vector<std::vector<int>> bands_by_branch;
  TreeTubes tubes;
  std::vector<std::vector<double>> rest_arcs;  // per branch

  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  RTCGeometry tree_geometry = nullptr;
  RTCGeometry rope_geometry = nullptr;
  std::vector<GeometryInfo> geometries;  // by Embree geometry id
  std::vector<CurveTable> curve_tables;
  int rope_table = -1;

  // One small scene per tape band: the triangles of the band's branch near the band only.
  struct BandScene {
    RTCScene scene = nullptr;
    RTCGeometry geometry = nullptr;
    std::vector<int> triangles;  // tree triangle index of each band-scene triangle
  };
  std::vector<BandScene> band_scenes;

  std::string embree_error;

  ~Impl() {
    for (BandScene& b : band_scenes) {
      if (b.scene) rtcReleaseScene(b.scene);
    }
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void CheckEmbree(const char* what) {
    const RTCError code = rtcGetDeviceError(device);
    if (code != RTC_ERROR_NONE || !embree_error.empty()) {
      throw Error(std::string("embree failed in ") + what + ": " +
                  (embree_error.empty() ? "error " + std::to_string(code) : embree_error));
    }
  }

  unsigned Attach(RTCGeometry geometry, const GeometryInfo& info) {
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);  // the scene holds it
    if (geometries.size() <= id) geometries.resize(id + 1);
    geometries[id] = info;
    return id;
  }

  // A triangle geometry with room for `vertices` and `triangles`; returns the buffers.
  RTCGeometry NewTriangles(size_t vertices, size_t triangles, float** vertex_data,
                           uint32_t** index_data) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    *vertex_data = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
    *index_data = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles));
    return g;
  }

  void AttachMesh(const TriangleMesh& mesh, const GeometryInfo& info) {
    float* v = nullptr;
    uint32_t* t = nullptr;
    RTCGeometry g = NewTriangles(mesh.vertices.size(), mesh.triangles.size(), &v, &t);
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      for (int c = 0; c < 3; ++c) v[3 * i + c] = mesh.vertices[i][c];
    }
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      for (int c = 0; c < 3; ++c) t[3 * i + c] = static_cast<uint32_t>(mesh.triangles[i][c]);
    }
    Attach(g, info);
  }

  unsigned AttachCurves(const CurveSet& curves, GeometryInfo info) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
    auto* v =
        static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                    4 * sizeof(float), curves.vertices.size()));
    auto* index = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), curves.segments.size()));
    auto* flags = static_cast<uint8_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, curves.segments.size()));
    for (size_t i = 0; i < curves.vertices.size(); ++i) {
      for (int c = 0; c < 4; ++c) v[4 * i + c] = curves.vertices[i][c];
    }
    std::copy(curves.segments.begin(), curves.segments.end(), index);
    std::copy(curves.flags.begin(), curves.flags.end(), flags);
    info.curves = static_cast<int>(curve_tables.size());
    curve_tables.push_back(MakeCurveTable(curves));
    return Attach(g, info);
  }

  void IndexMarkers() {
    bands_by_branch.assign(tree.size(), {});
    if (!options.markers) return;
    for (size_t m = 0; m < tree.markers.size(); ++m) {
      const Marker& marker = tree.markers[m];
      if (marker.branch < 0 || marker.branch >= tree.size() || !std::isfinite(marker.arc_length)) {
        throw InputError("<memory>", "tree.markers[" + std::to_string(m) + "]",
                         "expected a marker on an existing branch at a finite arc length");
      }
      MarkerBand band;
      band.marker_index = static_cast<int>(m);
      band.id = marker.id;
      band.branch = marker.branch;
      band.begin = marker.arc_length - 0.5 * options.tape_width_m;
      band.end = marker.arc_length + 0.5 * options.tape_width_m;
      bands_by_branch[band.branch].push_back(static_cast<int>(bands.size()));
      bands.push_back(band);
    }
  }

  void BuildTree() {
    float* v = nullptr;
    uint32_t* t = nullptr;
    tree_geometry = NewTriangles(tubes.vertex_count(), tubes.triangle_count(), &v, &t);
    tubes.WriteVertices(tree, pose, v);
    for (int i = 0; i < tubes.triangle_count(); ++i) {
      for (int c = 0; c < 3; ++c) t[3 * i + c] = static_cast<uint32_t>(tubes.triangles()[i][c]);
    }
    // A new pose refits the tree's bounding volume hierarchy instead of rebuilding it.
    rtcSetGeometryBuildQuality(tree_geometry, RTC_BUILD_QUALITY_REFIT);
    Attach(tree_geometry, GeometryInfo{.kind = SurfaceKind::kBranch, .object = SceneObject::kTree});
  }

  void BuildBandScenes() {
    for (const MarkerBand& band : bands) {
      const Branch& b = tree.branches[band.branch];
      BandScene out;
      out.scene = rtcNewScene(device);
      // The band's segments and one more on each side, so the band's surface and everything of
      // its own branch that can hide it from nearby are the same triangles as in the full tree.
      const int segments = static_cast<int>(b.nodes.size()) - 1;
      int lo = segments;
      int hi = -1;
      for (int i = 0; i < segments; ++i) {
        if (rest_arcs[band.branch][i + 1] >= band.begin && rest_arcs[band.branch][i] <= band.end) {
          lo = std::min(lo, i);
          hi = std::max(hi, i);
        }
      }
      if (hi >= 0) {
        lo = std::max(0, lo - 1);
        hi = std::min(segments - 1, hi + 1);
        const int first = tubes.triangle_offset(band.branch);
        const int end = band.branch + 1 < tree.size() ? tubes.triangle_offset(band.branch + 1)
                                                      : tubes.triangle_count();
        const int first_segment = tubes.first_segment(band.branch);
        for (int tri = first; tri < end; ++tri) {
          const int segment = tubes.triangle_segment(tri) - first_segment;
          if (segment >= lo && segment <= hi) out.triangles.push_back(tri);
        }
        float* v = nullptr;
        uint32_t* t = nullptr;
        const int vertex_offset = tubes.vertex_offset(band.branch);
        out.geometry =
            NewTriangles(tubes.branch_vertex_count(band.branch), out.triangles.size(), &v, &t);
        tubes.WriteBranchVertices(tree, pose, band.branch, v);
        for (size_t i = 0; i < out.triangles.size(); ++i) {
          for (int c = 0; c < 3; ++c) {
            t[3 * i + c] =
                static_cast<uint32_t>(tubes.triangles()[out.triangles[i]][c] - vertex_offset);
          }
        }
        rtcSetGeometryBuildQuality(out.geometry, RTC_BUILD_QUALITY_REFIT);
        rtcCommitGeometry(out.geometry);
        rtcAttachGeometry(out.scene, out.geometry);
        rtcReleaseGeometry(out.geometry);  // the band scene holds it
      }
      rtcCommitScene(out.scene);
      band_scenes.push_back(std::move(out));
    }
  }

  void UpdateTree() {
    auto* v =
        static_cast<float*>(rtcGetGeometryBufferData(tree_geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    tubes.WriteVertices(tree, pose, v);
    rtcUpdateGeometryBuffer(tree_geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(tree_geometry);
    for (size_t i = 0; i < band_scenes.size(); ++i) {
      BandScene& band = band_scenes[i];
      if (!band.geometry) continue;
      auto* bv =
          static_cast<float*>(rtcGetGeometryBufferData(band.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
      tubes.WriteBranchVertices(tree, pose, bands[i].branch, bv);
      rtcUpdateGeometryBuffer(band.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
      rtcCommitGeometry(band.geometry);
      rtcCommitScene(band.scene);
    }
    UpdateRope();
  }

  void UpdateRope() {
    if (!rope) {
      rtcDisableGeometry(rope_geometry);
      rtcCommitGeometry(rope_geometry);
      return;
    }
    const Eigen::Vector3d start = pose.PointAt(tree, rope->branch, rope->arc_length);
    auto* v =
        static_cast<float*>(rtcGetGeometryBufferData(rope_geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    const float r = static_cast<float>(options.rope_radius_m);
    const Eigen::Vector3d points[2] = {start, rope->anchor};
    for (int i = 0; i < 2; ++i) {
      v[4 * i + 0] = static_cast<float>(points[i].x());
      v[4 * i + 1] = static_cast<float>(points[i].y());
      v[4 * i + 2] = static_cast<float>(points[i].z());
      v[4 * i + 3] = r;
    }
    curve_tables[rope_table].length[0] = static_cast<float>((rope->anchor - start).norm());
    rtcUpdateGeometryBuffer(rope_geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcEnableGeometry(rope_geometry);
    rtcCommitGeometry(rope_geometry);
  }

  // The hit's point, facing normal and t from Embree's answer.
  static void FillGeometry(const RTCRayHit& rh, const Eigen::Vector3d& origin,
                           const Eigen::Vector3d& direction, SceneHit& hit) {
    hit.t = rh.ray.tfar;
    hit.point = origin + hit.t * direction;
    Eigen::Vector3d n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    n.normalize();
    hit.normal = n.dot(direction) > 0.0 ? Eigen::Vector3d(-n) : n;
  }

  SceneHit MakeHit(const RTCRayHit& rh, const Eigen::Vector3d& origin,
                   const Eigen::Vector3d& direction) const {
    SceneHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    const GeometryInfo& info = geometries[rh.hit.geomID];
    hit.kind = info.kind;
    hit.object = info.object;
    hit.object_index = info.object_index;
    FillGeometry(rh, origin, direction, hit);
    if (info.object == SceneObject::kTree) {
      FillBranchHit(static_cast<int>(rh.hit.primID), origin, direction, hit);
    } else if (info.curves >= 0) {
      const double u = std::clamp(static_cast<double>(rh.hit.u), 0.0, 1.0);
      const CurveTable& table = curve_tables[info.curves];
      const unsigned p = rh.hit.primID;
      hit.along = table.along0[p] + u * table.length[p];
      hit.radius = table.radius0[p] + u * (table.radius1[p] - table.radius0[p]);
    } else if (info.object == SceneObject::kHedge) {
      const Eigen::Vector2d d = hit.point.head<2>() - options.hedge_center;
      hit.along = std::atan2(d.y(), d.x()) * options.hedge_radius_m;
    }
    return hit;
  }

  // Moves a hit on a tube facet of segment `i` of branch `b` onto the true surface (the cone
  // frustum of that segment or of a neighbour, since the facet lies up to the tolerance inside
  // it); `i` becomes the segment hit. Keeps the facet hit when no frustum is met (a ray through
  // a joint's crease).
  void RefineOnTrueSurface(int b, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                           SceneHit& hit, int& i) const {
    const Branch& branch = tree.branches[b];
    const int last = static_cast<int>(branch.nodes.size()) - 2;
    std::optional<double> best;
    int best_segment = i;
    for (int j = std::max(0, i - 1); j <= std::min(last, i + 1); ++j) {
      const std::optional<double> t =
          IntersectFrustum(origin, direction, pose.node(b, j), pose.node(b, j + 1),
                           branch.nodes[j].radius, branch.nodes[j + 1].radius);
      // Only the surface just in front of the facet (a few tolerances), not another side.
      if (t && *t <= hit.t * (1.0 + 1e-6) && *t >= hit.t - 0.01 / direction.norm() &&
          (!best || *t < *best)) {
        best = t;
        best_segment = j;
      }
    }
    if (!best) return;
    hit.t = *best;
    hit.point = origin + hit.t * direction;
    i = best_segment;
  }

  // Branch, rest arc length, radius, angle, smooth normal and marker of a hit on tube triangle
  // `triangle` (hit.point, t and the facet normal already set).
  void FillBranchHit(int triangle, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                     SceneHit& hit) const {
    const int segment = tubes.triangle_segment(triangle);
    const int b = tubes.segment_branch(segment);
    int i = tubes.segment_node(segment);
    const Branch& branch = tree.branches[b];
    if (!tubes.triangle_is_cap(triangle)) RefineOnTrueSurface(b, origin, direction, hit, i);
    const Eigen::Vector3d p0 = pose.node(b, i);
    const Eigen::Vector3d axis = pose.node(b, i + 1) - p0;
    const double length2 = axis.squaredNorm();
    const double u =
        length2 > 0.0 ? std::clamp((hit.point - p0).dot(axis) / length2, 0.0, 1.0) : 0.0;
    const double r0 = branch.nodes[i].radius;
    const double r1 = branch.nodes[i + 1].radius;
    hit.branch = b;
    hit.arc_length = rest_arcs[b][i] + u * (rest_arcs[b][i + 1] - rest_arcs[b][i]);
    hit.radius = r0 + u * (r1 - r0);
    Eigen::Vector3d radial = hit.point - (p0 + u * axis);
    if (length2 > 0.0) radial -= radial.dot(axis) / length2 * axis;
    hit.angle = std::atan2(radial.dot(branch.frame.w), radial.dot(branch.frame.u));
    // The true surface's normal (not the facet's): radial, tilted by the taper.
    if (!tubes.triangle_is_cap(triangle) && radial.squaredNorm() > 0.0 && length2 > 0.0) {
      const double length = std::sqrt(length2);
      Eigen::Vector3d n = radial.normalized() - (r1 - r0) / length * (axis / length);
      n.normalize();
      hit.normal = n.dot(direction) > 0.0 ? Eigen::Vector3d(-n) : n;
    }
    for (int k : bands_by_branch[b]) {
      const MarkerBand& band = bands[k];
      if (hit.arc_length >= band.begin && hit.arc_length <= band.end) {
        hit.marker = band.id;
        hit.marker_index = band.marker_index;
        break;
      }
    }
  }
};

SensorScene::SensorScene(const Tree& tree, const SceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Validate(tree, "tree");
  ValidateSceneOptions(options, "scene options");
  Impl& m = *impl_;
  m.tree = tree;
  m.pose = TreePose(tree);
  m.options = options;
  m.tubes = TreeTubes(tree, TreeTubeOptions{.tolerance_m = options.tube_tolerance_m});
  m.rest_arcs.resize(tree.size());
  for (const Branch& b : tree.branches) m.rest_arcs[b.id] = b.ArcLengths();
  m.IndexMarkers();

  m.device = rtcNewDevice(nullptr);
  if (!m.device) throw Error("embree: cannot create a device");
  rtcSetDeviceErrorFunction(
      m.device,
      [](void* user, RTCError, const char* message) {
        static_cast<Impl*>(user)->embree_error = message ? message : "unknown error";
      },
      &m);
  m.scene = rtcNewScene(m.device);
  // Measured on tree02 (84k tube triangles): a dynamic, low-quality scene with a refitted tree
  // commits a new pose in ~2 ms and traces as fast as a high-quality one; the default rebuild
  // takes ~25 ms.
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_LOW);
  m.BuildTree();
  // The rope: one segment, disabled until SetRope.
  {
    CurveSet rope;
    rope.AddPolyline({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()},
                     {options.rope_radius_m, options.rope_radius_m});
    m.rope_table = static_cast<int>(m.curve_tables.size());
    const unsigned id = m.AttachCurves(
        rope, GeometryInfo{.kind = SurfaceKind::kRope, .object = SceneObject::kRope});
    m.rope_geometry = rtcGetGeometry(m.scene, id);
    rtcDisableGeometry(m.rope_geometry);
    rtcCommitGeometry(m.rope_geometry);
  }
  if (options.ground) {
    m.AttachMesh(GroundMesh(options.hedge_center, options.ground_half_size_m),
                 GeometryInfo{.kind = SurfaceKind::kGround, .object = SceneObject::kGround});
  }
  if (options.hedge) {
    m.AttachMesh(HedgeRingMesh(options.hedge_center, options.hedge_radius_m, options.hedge_height_m,
                               options.texture_seed),
                 GeometryInfo{.kind = SurfaceKind::kBackground, .object = SceneObject::kHedge});
  }
  for (size_t i = 0; i < options.boxes.size(); ++i) {
    m.AttachMesh(BoxMesh(options.boxes[i]), GeometryInfo{.kind = options.boxes[i].kind,
                                                         .object = SceneObject::kBox,
                                                         .object_index = static_cast<int>(i)});
  }
  for (size_t i = 0; i < options.posts.size(); ++i) {
    m.AttachCurves(PostCurves(options.posts[i]), GeometryInfo{.kind = SurfaceKind::kOccluder,
                                                              .object = SceneObject::kPost,
                                                              .object_index = static_cast<int>(i)});
  }
  for (size_t i = 0; i < options.shrubs.size(); ++i) {
    m.AttachCurves(ShrubCurves(options.shrubs[i]),
                   GeometryInfo{.kind = SurfaceKind::kOccluder,
                                .object = SceneObject::kShrub,
                                .object_index = static_cast<int>(i)});
  }
  rtcCommitScene(m.scene);
  m.BuildBandScenes();
  m.CheckEmbree("building the scene");
}

SensorScene::~SensorScene() = default;
SensorScene::SensorScene(SensorScene&&) noexcept = default;
SensorScene& SensorScene::operator=(SensorScene&&) noexcept = default;

void SensorScene::SetPose(const TreePose& pose) {
  Impl& m = *impl_;
  if (pose.branch_count() != m.tree.size()) {
    throw InputError("<memory>", "tree pose",
                     "expected " + std::to_string(m.tree.size()) + " branches, got " +
                         std::to_string(pose.branch_count()));
  }
  for (const Branch& b : m.tree.branches) {
    if (pose.node_count(b.id) != static_cast<int>(b.nodes.size())) {
      throw InputError("<memory>", "tree pose, branch " + std::to_string(b.id),
                       "expected " + std::to_string(b.nodes.size()) + " nodes, got " +
                           std::to_string(pose.node_count(b.id)));
    }
  }
  for (int i = 0; i < pose.node_count(); ++i) {
    if (!pose.positions()[i].allFinite()) {
      throw InputError("<memory>", "tree pose, node " + std::to_string(i),
                       "expected a finite position");
    }
  }
  m.pose = pose;
  m.UpdateTree();
  rtcCommitScene(m.scene);
  m.CheckEmbree("updating the tree pose");
}

void SensorScene::SetRope(const std::optional<RopeSegment>& rope) {
  Impl& m = *impl_;
  if (rope) {
    if (rope->branch < 0 || rope->branch >= m.tree.size()) {
      throw InputError("<memory>", "rope.branch",
                       "expected a branch id in [0, " + std::to_string(m.tree.size()) + "), got " +
                           std::to_string(rope->branch));
    }
    if (!std::isfinite(rope->arc_length) || !rope->anchor.allFinite()) {
      throw InputError("<memory>", "rope", "expected a finite arc length and anchor");
    }
  }
  m.rope = rope;
  m.UpdateRope();
  rtcCommitScene(m.scene);
  m.CheckEmbree("updating the rope");
}

const Tree& SensorScene::tree() const { return impl_->tree; }
const TreePose& SensorScene::pose() const { return impl_->pose; }
const SceneOptions& SensorScene::options() const { return impl_->options; }
const std::optional<RopeSegment>& SensorScene::rope() const { return impl_->rope; }
const std::vector<MarkerBand>& SensorScene::marker_bands() const { return impl_->bands; }

SceneHit SensorScene::Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                double t_near, double t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  InitRay(rh.ray, origin, direction, t_near, t_far);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  return impl_->MakeHit(rh, origin, direction);
}

void SensorScene::IntersectCoherent(const Eigen::Vector3d& origin,
                                    std::span<const Eigen::Vector3d> directions,
                                    std::span<SceneHit> hits) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacket];
  for (size_t start = 0; start < directions.size(); start += kPacket) {
    const size_t n = std::min(kPacket, directions.size() - start);
    for (size_t i = 0; i < kPacket; ++i) {
      valid[i] = i < n ? -1 : 0;
      InitRayLane(packet.ray, i, origin, directions[start + std::min(i, n - 1)], 0.0,
                  std::numeric_limits<double>::infinity());
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, impl_->scene, &context, &packet);
    for (size_t i = 0; i < n; ++i) {
      RTCRayHit one;
      one.ray.tfar = packet.ray.tfar[i];
      one.hit.geomID = packet.hit.geomID[i];
      one.hit.primID = packet.hit.primID[i];
      one.hit.u = packet.hit.u[i];
      one.hit.v = packet.hit.v[i];
      one.hit.Ng_x = packet.hit.Ng_x[i];
      one.hit.Ng_y = packet.hit.Ng_y[i];
      one.hit.Ng_z = packet.hit.Ng_z[i];
      hits[start + i] = impl_->MakeHit(one, origin, directions[start + i]);
    }
  }
}

bool SensorScene::Occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                           double t_near, double t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  InitRay(ray, origin, direction, t_near, t_far);
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void SensorScene::OccludedCoherent(std::span<const Eigen::Vector3d> origins,
                                   const Eigen::Vector3d& direction, double t_near, double t_far,
                                   std::span<uint8_t> occluded) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRay16 packet;
  alignas(64) int valid[kPacket];
  for (size_t start = 0; start < origins.size(); start += kPacket) {
    const size_t n = std::min(kPacket, origins.size() - start);
    for (size_t i = 0; i < kPacket; ++i) {
      valid[i] = i < n ? -1 : 0;
      InitRayLane(packet, i, origins[start + std::min(i, n - 1)], direction, t_near, t_far);
    }
    rtcOccluded16(valid, impl_->scene, &context, &packet);
    for (size_t i = 0; i < n; ++i) occluded[start + i] = packet.tfar[i] < 0.0f;
  }
}

SceneHit SensorScene::IntersectMarkerBand(int marker_index, const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& direction) const {
  const Impl& m = *impl_;
  SceneHit none;
  if (marker_index < 0 || marker_index >= static_cast<int>(m.band_scenes.size())) return none;
  const Impl::BandScene& band = m.band_scenes[marker_index];
  if (!band.geometry) return none;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  InitRay(rh.ray, origin, direction, 0.0, std::numeric_limits<double>::infinity());
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(band.scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return none;
  SceneHit hit;
  hit.kind = SurfaceKind::kBranch;
  hit.object = SceneObject::kTree;
  Impl::FillGeometry(rh, origin, direction, hit);
  m.FillBranchHit(band.triangles[rh.hit.primID], origin, direction, hit);
  if (hit.marker_index != marker_index) return none;
  return hit;
}

double SensorScene::RadiusAt(int branch, double arc_length) const {
  const Impl& m = *impl_;
  const Branch& b = m.tree.branches.at(branch);
  const std::vector<double>& s = m.rest_arcs[branch];
  if (b.nodes.size() < 2 || arc_length <= 0.0) return b.nodes.front().radius;
  for (size_t i = 1; i < s.size(); ++i) {
    if (arc_length <= s[i]) {
      const double span = s[i] - s[i - 1];
      const double t = span > 0 ? (arc_length - s[i - 1]) / span : 0.0;
      return b.nodes[i - 1].radius + t * (b.nodes[i].radius - b.nodes[i - 1].radius);
    }
  }
  return b.nodes.back().radius;
}

}  // namespace simtree::synth
