#pragma once
// Cameras of the viewer and the renderer: an orbit camera (turn, pan and zoom about a target, Z up)
// and a pinhole camera from a capture's intrinsics and pose (OpenCV axes), both giving the OpenGL
// matrices, the ray under a pixel (picking) and the pixel of a point.
//
// Pixels are indexed from the top-left corner, x right and y down, pixel (i, j) covering
// [i, i + 1) x [j, j + 1) (window and screenshot coordinates; a CameraIntrinsics pixel centre at
// integer (u, v) is pixel (u + 0.5, v + 0.5) here).

#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/io/capture.h"

namespace simtree::viewer {

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit
};

// What a frame is drawn with.
struct CameraView {
  int width = 1;
  int height = 1;
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();        // world to eye (eye looks down -z)
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();  // eye to clip

  Eigen::Vector3d EyePosition() const;
  // Looking direction (unit, world).
  Eigen::Vector3d Forward() const;
  // The ray through window point (x, y) (continuous pixel coordinates, see above).
  Ray PixelRay(double x, double y) const;
  // The window point of a world point; nullopt behind the camera.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& world) const;
  // World size of one pixel at distance `depth` along the view direction.
  double PixelSizeAt(double depth) const;
};

struct OrbitCamera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double yaw_rad = -1.5707963267948966;  // eye at -Y: looking along +Y
  double pitch_rad = 0.15;               // eye above the target's horizon
  double distance_m = 5.0;
  double fov_y_rad = 0.785398;  // 45 degrees

  // Eye position in the world.
  Eigen::Vector3d Eye() const;
  // Turns about the target (pitch kept within +-89 degrees).
  void Orbit(double dyaw_rad, double dpitch_rad);
  // Moves the target across the view by a window displacement (pixels) in a window `height` tall.
  void Pan(double dx_px, double dy_px, int height);
  // Distance times `factor` (< 1 comes closer), kept positive.
  void Zoom(double factor);
  // Targets the centre of a box and backs off until it fits the view.
  void Frame(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner, double aspect);
  CameraView View(int width, int height) const;
};

// The view of a calibrated camera: its intrinsics (image size and focal lengths) and its pose
// world_from_camera (OpenCV axes: x right, y down, z forward). Near and far planes in metres.
CameraView PinholeView(const CameraIntrinsics& intrinsics,
                       const Eigen::Isometry3d& world_from_camera, double near_m = 0.05,
                       double far_m = 100.0);

}  // namespace simtree::viewer
