#pragma once
// The static props of the sensor scene as plain geometry (triangle meshes and curve sets), before
// they go to Embree: ground, hedge ring, boxes, posts, shrubs. Kept apart from sensor_scene.cc so
// their shapes can be checked without ray casting.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/mesh.h"
#include "simtree/synth/detail/sensor_scene.h"

namespace simtree::synth {

// Polylines with a radius per vertex, as Embree's round linear curves take them: `segments` holds
// the first vertex of every segment (the segment runs to the next vertex).
struct CurveSet {
  std::vector<Eigen::Vector4f> vertices;  // x, y, z, radius
  std::vector<uint32_t> segments;
  std::vector<uint8_t> flags;  // RTC_CURVE_FLAG_NEIGHBOR_LEFT / _RIGHT per segment
  std::vector<float> along;    // per vertex: distance from its polyline's start
  // Appends a polyline (at least two points).
  void AddPolyline(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& radii);
};

TriangleMesh GroundMesh(const Eigen::Vector2d& center, double half_size_m);
// A bumpy ring of hedge (inward-facing wall) of `radius_m` and `height_m`.
TriangleMesh HedgeRingMesh(const Eigen::Vector2d& center, double radius_m, double height_m,
                           uint64_t seed);
TriangleMesh BoxMesh(const SceneBox& box);
CurveSet PostCurves(const ScenePost& post);
CurveSet ShrubCurves(const SceneShrub& shrub);

}  // namespace simtree::synth
