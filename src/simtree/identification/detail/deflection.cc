#include "simtree/identification/detail/deflection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "simtree/core/frames.h"

namespace simtree::identification {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Mean valid position over frames [begin, end); NaN when none is valid.
Eigen::Vector3d MeanPosition(const MarkerTrack& track, int begin, int end) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (int i = begin; i < end; ++i) {
    if (!track.valid[i]) continue;
    sum += track.positions[i];
    ++count;
  }
  return count ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Constant(kNaN);
}

}  // namespace

const char* ToString(DeflectionKind kind) {
  return kind == DeflectionKind::kRelativeAngle ? "relative_angle" : "displacement";
}

std::vector<DeflectionLink> LinksFromMarkers(const std::vector<MarkerLink>& markers,
                                             bool include_root) {
  std::map<int, const MarkerLink*> by_id;
  for (const MarkerLink& m : markers) by_id[m.id] = &m;
  std::vector<DeflectionLink> links;
  for (const MarkerLink& m : markers) {
    DeflectionLink link;
    link.child = m.id;
    link.parent = m.parent;
    link.branch = m.branch;
    if (m.parent < 0) {
      if (!include_root) continue;
      link.label = m.label;
    } else {
      const auto it = by_id.find(m.parent);
      const MarkerLink* parent = it == by_id.end() ? nullptr : it->second;
      link.grandparent = parent ? parent->parent : -1;
      link.label = (parent ? parent->label : fmt::format("M{}", m.parent)) + "-" + m.label;
    }
    links.push_back(std::move(link));
  }
  // The root first: it is the trunk's value and the reference of the others.
  std::stable_partition(links.begin(), links.end(),
                        [](const DeflectionLink& l) { return l.is_root(); });
  return links;
}

std::vector<DeflectionSignal> ComputeDeflectionSignals(const Trajectories& t,
                                                       const std::vector<DeflectionLink>& links,
                                                       int first_frame, int end_frame,
                                                       const DeflectionOptions& options) {
  if (end_frame < 0 || end_frame > t.frame_count()) end_frame = t.frame_count();
  first_frame = std::clamp(first_frame, 0, end_frame);
  const int frames = end_frame - first_frame;
  const int rest_begin =
      end_frame - std::max(1, static_cast<int>(std::lround(frames * options.rest_fraction)));
  const std::vector<double> times(t.times_s.begin() + first_frame, t.times_s.begin() + end_frame);
  std::vector<DeflectionSignal> out;
  for (const DeflectionLink& link : links) {
    DeflectionSignal d;
    d.link = link;
    d.kind = link.is_root() ? DeflectionKind::kDisplacement : DeflectionKind::kRelativeAngle;
    const MarkerTrack* child = t.Find(link.child);
    const MarkerTrack* parent = link.is_root() ? nullptr : t.Find(link.parent);
    const MarkerTrack* grandparent = link.grandparent < 0 ? nullptr : t.Find(link.grandparent);
    for (int id : {link.child, link.parent, link.grandparent}) {
      if (id >= 0 && !t.Find(id) && d.problem.empty()) {
        d.problem = fmt::format(
            "marker {} has no trajectory (it is in the marker list but not "
            "in the trajectories)",
            id);
      }
    }
    if (frames < 2 && d.problem.empty()) d.problem = "fewer than 2 frames in the record";
    if (!d.problem.empty()) {
      out.push_back(std::move(d));
      continue;
    }
    Eigen::MatrixXd values(frames, 2);
    std::vector<bool> valid(frames, false);
    const Eigen::Vector3d child_rest = MeanPosition(*child, rest_begin, end_frame);
    if (link.is_root()) {
      if (!child_rest.allFinite()) {
        d.problem = fmt::format("marker {} is never valid at the end of the record", link.child);
        out.push_back(std::move(d));
        continue;
      }
      // The two directions the marker moves most (principal axes of its displacement).
      Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
      for (int i = first_frame; i < end_frame; ++i) {
        if (!child->valid[i]) continue;
        const Eigen::Vector3d x = child->positions[i] - child_rest;
        scatter += x * x.transpose();
      }
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
      d.u = eig.eigenvectors().col(2);
      d.w = eig.eigenvectors().col(1);
      d.v = d.u.cross(d.w);
      for (int i = first_frame; i < end_frame; ++i) {
        const int j = i - first_frame;
        valid[j] = child->valid[i];
        const Eigen::Vector3d x = child->positions[i] - child_rest;
        values(j, 0) = valid[j] ? x.dot(d.u) : kNaN;
        values(j, 1) = valid[j] ? x.dot(d.w) : kNaN;
      }
      d.signal = ResampleOnGrid(times, values, valid, link.label);
      d.signal.channel_names = {"d_1", "d_2"};
      out.push_back(std::move(d));
      continue;
    }
    const Eigen::Vector3d parent_rest = MeanPosition(*parent, rest_begin, end_frame);
    const Eigen::Vector3d grandparent_rest =
        grandparent ? MeanPosition(*grandparent, rest_begin, end_frame) : Eigen::Vector3d::Zero();
    if (!child_rest.allFinite() || !parent_rest.allFinite() || !grandparent_rest.allFinite()) {
      d.problem = "a marker of the link is never valid at the end of the record (no rest pose)";
      out.push_back(std::move(d));
      continue;
    }
    const Eigen::Vector3d link_rest = child_rest - parent_rest;
    d.rest_length_m = link_rest.norm();
    if (d.rest_length_m < 1e-6) {
      d.problem = fmt::format("markers {} and {} coincide at rest", link.parent, link.child);
      out.push_back(std::move(d));
      continue;
    }
    const Eigen::Vector3d parent_axis =
        grandparent ? Eigen::Vector3d((parent_rest - grandparent_rest).normalized())
                    : options.camera_up.normalized();
    const Frame frame =
        FrameFromAxes(link_rest / d.rest_length_m, parent_axis, Eigen::Vector3d::UnitX());
    d.u = frame.u;
    d.v = frame.v;
    d.w = frame.w;
    for (int i = first_frame; i < end_frame; ++i) {
      const int j = i - first_frame;
      valid[j] = child->valid[i] && parent->valid[i] && (!grandparent || grandparent->valid[i]);
      values.row(j).setConstant(kNaN);
      if (!valid[j]) continue;
      Eigen::Vector3d direction = (child->positions[i] - parent->positions[i]).normalized();
      if (grandparent) {
        // Undo the parent link's swing: the shortest rotation taking its rest direction to its
        // current one.
        const Eigen::Vector3d now = (parent->positions[i] - grandparent->positions[i]).normalized();
        const Eigen::Quaterniond swing = Eigen::Quaterniond::FromTwoVectors(parent_axis, now);
        direction = swing.conjugate() * direction;
      }
      values(j, 0) = std::atan2(direction.dot(d.u), direction.dot(d.v));
      values(j, 1) = std::atan2(direction.dot(d.w), direction.dot(d.v));
    }
    d.signal = ResampleOnGrid(times, values, valid, link.label);
    d.signal.channel_names = {"theta_u", "theta_w"};
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace simtree::identification
