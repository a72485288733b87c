#include "simtree/viewer/detail/camera.h"

#include <algorithm>
#include <cmath>

namespace simtree::viewer {
namespace {

Eigen::Matrix4d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                       const Eigen::Vector3d& up) {
  const Eigen::Vector3d f = (target - eye).normalized();
  Eigen::Vector3d s = f.cross(up);
  if (s.norm() < 1e-9) s = f.unitOrthogonal();
  s.normalize();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4d Perspective(double fov_y, double aspect, double near_m, double far_m) {
  const double f = 1.0 / std::tan(fov_y / 2.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = -(far_m + near_m) / (far_m - near_m);
  m(2, 3) = -2.0 * far_m * near_m / (far_m - near_m);
  m(3, 2) = -1.0;
  return m;
}

}  // namespace

Eigen::Vector3d CameraView::EyePosition() const {
  const Eigen::Matrix3d r = view.block<3, 3>(0, 0);
  return -r.transpose() * view.block<3, 1>(0, 3);
}

Eigen::Vector3d CameraView::Forward() const {
  return -view.block<1, 3>(2, 0).transpose().normalized();
}

Ray CameraView::PixelRay(double x, double y) const {
  const double ndc_x = 2.0 * x / width - 1.0;
  const double ndc_y = 1.0 - 2.0 * y / height;
  const Eigen::Matrix4d inverse = (projection * view).inverse();
  auto unproject = [&](double z) {
    const Eigen::Vector4d p = inverse * Eigen::Vector4d(ndc_x, ndc_y, z, 1.0);
    return Eigen::Vector3d(p.head<3>() / p.w());
  };
  const Eigen::Vector3d a = unproject(-1.0), b = unproject(1.0);
  return {a, (b - a).normalized()};
}

std::optional<Eigen::Vector2d> CameraView::Project(const Eigen::Vector3d& world) const {
  const Eigen::Vector4d clip = projection * view * world.homogeneous();
  if (clip.w() <= 1e-12) return std::nullopt;
  const double ndc_x = clip.x() / clip.w(), ndc_y = clip.y() / clip.w();
  return Eigen::Vector2d((ndc_x + 1.0) * 0.5 * width, (1.0 - ndc_y) * 0.5 * height);
}

double CameraView::PixelSizeAt(double depth) const {
  // projection(1, 1) is 2 fy / height for a pinhole and 1 / tan(fov / 2) for a perspective.
  return 2.0 * depth / (projection(1, 1) * height);
}

Eigen::Vector3d OrbitCamera::Eye() const {
  const Eigen::Vector3d dir(std::cos(pitch_rad) * std::cos(yaw_rad),
                            std::cos(pitch_rad) * std::sin(yaw_rad), std::sin(pitch_rad));
  return target + distance_m * dir;
}

void OrbitCamera::Orbit(double dyaw_rad, double dpitch_rad) {
  yaw_rad = std::remainder(yaw_rad + dyaw_rad, 2.0 * M_PI);
  pitch_rad = std::clamp(pitch_rad + dpitch_rad, -1.55, 1.55);
}

void OrbitCamera::Pan(double dx_px, double dy_px, int height) {
  const CameraView v = View(height, std::max(height, 1));
  const Eigen::Vector3d right = v.view.block<1, 3>(0, 0).transpose();
  const Eigen::Vector3d up = v.view.block<1, 3>(1, 0).transpose();
  const double metres_per_px = v.PixelSizeAt(distance_m);
  target += metres_per_px * (-dx_px * right + dy_px * up);
}

void OrbitCamera::Zoom(double factor) {
  if (factor > 0.0 && std::isfinite(factor)) distance_m = std::max(1e-3, distance_m * factor);
}

void OrbitCamera::Frame(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner,
                        double aspect) {
  target = 0.5 * (min_corner + max_corner);
  // Back off until the box's silhouette from this direction fits both field-of-view angles.
  const Eigen::Vector3d half = 0.5 * (max_corner - min_corner);
  const double tan_y = std::tan(fov_y_rad / 2.0);
  const double tan_x = tan_y * std::max(aspect, 1e-3);
  const double horizontal = std::hypot(half.x(), half.y());
  const double depth = horizontal;  // the box reaches at most this far towards the eye
  const double vertical =
      half.z() * std::cos(pitch_rad) + horizontal * std::abs(std::sin(pitch_rad));
  distance_m = std::max({1e-3, vertical / tan_y, horizontal / tan_x}) + depth;
}

CameraView OrbitCamera::View(int width, int height) const {
  CameraView v;
  v.width = std::max(width, 1);
  v.height = std::max(height, 1);
  v.view = LookAt(Eye(), target, Eigen::Vector3d::UnitZ());
  const double near_m = std::max(1e-3, distance_m * 0.01);
  v.projection = Perspective(fov_y_rad, static_cast<double>(v.width) / v.height, near_m,
                             distance_m * 20.0 + 100.0);
  return v;
}

CameraView PinholeView(const CameraIntrinsics& k, const Eigen::Isometry3d& world_from_camera,
                       double near_m, double far_m) {
  CameraView v;
  v.width = k.width;
  v.height = k.height;
  // OpenCV camera axes (x right, y down, z forward) to OpenGL eye axes (x right, y up, z back).
  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();
  flip(1, 1) = -1.0;
  flip(2, 2) = -1.0;
  v.view = flip * world_from_camera.inverse().matrix();
  // A camera-frame point projects to (fx x / z + cx, fy y / z + cy) with pixel centres at integers,
  // i.e. at window coordinate u + 0.5.
  const double w = k.width, h = k.height;
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = 2.0 * k.fx / w;
  p(0, 2) = 1.0 - (2.0 * k.cx + 1.0) / w;
  p(1, 1) = 2.0 * k.fy / h;
  p(1, 2) = (2.0 * k.cy + 1.0) / h - 1.0;
  p(2, 2) = -(far_m + near_m) / (far_m - near_m);
  p(2, 3) = -2.0 * far_m * near_m / (far_m - near_m);
  p(3, 2) = -1.0;
  v.projection = p;
  return v;
}

}  // namespace simtree::viewer
