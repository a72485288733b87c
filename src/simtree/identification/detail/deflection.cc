#include "simtree/identification/detail/deflection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "simtree/core/frames.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::identification {
namespace {

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

// The frames the signals cover, [first, end), and the tail the rest pose is averaged over.
struct FrameRange {
  int first = 0, end = 0;
  int rest_begin = 0;
  std::vector<double> times;  // of frames [first, end)

  int size() const { return end - first; }
};

FrameRange RangeOf(const Trajectories& t, int first_frame, int end_frame,
                   const DeflectionOptions& options) {
  FrameRange r;
  r.end = end_frame < 0 || end_frame > t.frame_count() ? t.frame_count() : end_frame;
  r.first = std::clamp(first_frame, 0, r.end);
  r.rest_begin =
      r.end - std::max(1, static_cast<int>(std::lround(r.size() * options.rest_fraction)));
  r.times.assign(t.times_s.begin() + r.first, t.times_s.begin() + r.end);
  return r;
}

DeflectionSignal Unusable(const DeflectionLink& link, DeflectionStatus status,
                          std::string problem) {
  DeflectionSignal d;
  d.link = link;
  d.kind = link.is_root() ? DeflectionKind::kDisplacement : DeflectionKind::kRelativeAngle;
  d.status = status;
  d.problem = std::move(problem);
  return d;
}

// The link with no signal yet, its status kOk, or why it can have none before any position is
// read: a marker without a trajectory, or too short a record.
DeflectionSignal UnusableLink(const Trajectories& t, const DeflectionLink& link,
                              const FrameRange& range) {
  for (int id : {link.child, link.parent, link.grandparent}) {
    if (id >= 0 && !t.Find(id)) {
      return Unusable(link, DeflectionStatus::kMissingTrajectory,
                      fmt::format("marker {} has no trajectory (it is in the marker list but not "
                                  "in the trajectories)",
                                  id));
    }
  }
  if (range.size() < 2) {
    return Unusable(link, DeflectionStatus::kTooFewFrames, "fewer than 2 frames in the record");
  }
  return Unusable(link, DeflectionStatus::kOk, "");
}

// The root marker's motion from rest along the two directions it moves most (the principal axes
// of its displacement), in metres.
DeflectionSignal RootDisplacement(const DeflectionLink& link, const MarkerTrack& child,
                                  const FrameRange& range) {
  const Eigen::Vector3d rest = MeanPosition(child, range.rest_begin, range.end);
  if (!rest.allFinite()) {
    return Unusable(link, DeflectionStatus::kNoRestPose,
                    fmt::format("marker {} is never valid at the end of the record", link.child));
  }
  DeflectionSignal d = Unusable(link, DeflectionStatus::kOk, "");
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i = range.first; i < range.end; ++i) {
    if (!child.valid[i]) continue;
    const Eigen::Vector3d x = child.positions[i] - rest;
    scatter += x * x.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  d.u = eig.eigenvectors().col(2);
  d.w = eig.eigenvectors().col(1);
  d.v = d.u.cross(d.w);
  Eigen::MatrixXd values(range.size(), 2);
  std::vector<bool> valid(range.size(), false);
  for (int i = range.first; i < range.end; ++i) {
    const int j = i - range.first;
    valid[j] = child.valid[i];
    const Eigen::Vector3d x = child.positions[i] - rest;
    values(j, 0) = valid[j] ? x.dot(d.u) : kNaN;
    values(j, 1) = valid[j] ? x.dot(d.w) : kNaN;
  }
  d.signal = ResampleOnGrid(range.times, values, valid, link.label);
  d.signal.channel_names = {"d_1", "d_2"};
  return d;
}

// theta_u, theta_w of a link against its parent link (or the camera's up, from the root marker),
// with the parent link's swing taken out.
DeflectionSignal RelativeAngle(const Trajectories& t, const DeflectionLink& link,
                               const FrameRange& range, const DeflectionOptions& options) {
  const MarkerTrack* child = t.Find(link.child);
  const MarkerTrack* parent = t.Find(link.parent);
  const MarkerTrack* grandparent = link.grandparent < 0 ? nullptr : t.Find(link.grandparent);
  const Eigen::Vector3d child_rest = MeanPosition(*child, range.rest_begin, range.end);
  const Eigen::Vector3d parent_rest = MeanPosition(*parent, range.rest_begin, range.end);
  const Eigen::Vector3d grandparent_rest =
      grandparent ? MeanPosition(*grandparent, range.rest_begin, range.end)
                  : Eigen::Vector3d::Zero();
  if (!child_rest.allFinite() || !parent_rest.allFinite() || !grandparent_rest.allFinite()) {
    return Unusable(link, DeflectionStatus::kNoRestPose,
                    "a marker of the link is never valid at the end of the record (no rest pose)");
  }
  DeflectionSignal d = Unusable(link, DeflectionStatus::kOk, "");
  const Eigen::Vector3d link_rest = child_rest - parent_rest;
  d.rest_length_m = link_rest.norm();
  if (d.rest_length_m < 1e-6) {
    return Unusable(link, DeflectionStatus::kCoincidentMarkers,
                    fmt::format("markers {} and {} coincide at rest", link.parent, link.child));
  }
  const Eigen::Vector3d parent_axis =
      grandparent ? Eigen::Vector3d((parent_rest - grandparent_rest).normalized())
                  : options.camera_up.normalized();
  const Frame frame =
      FrameFromAxes(link_rest / d.rest_length_m, parent_axis, Eigen::Vector3d::UnitX());
  d.u = frame.u;
  d.v = frame.v;
  d.w = frame.w;
  Eigen::MatrixXd values(range.size(), 2);
  std::vector<bool> valid(range.size(), false);
  for (int i = range.first; i < range.end; ++i) {
    const int j = i - range.first;
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
  d.signal = ResampleOnGrid(range.times, values, valid, link.label);
  d.signal.channel_names = {"theta_u", "theta_w"};
  return d;
}

}  // namespace

void DeflectionOptions::Validate() const {
  if (!camera_up.allFinite() || !(camera_up.norm() > 0)) {
    throw OptionError("camera_up", fmt::format("expected a finite, non-zero direction, got ({}, "
                                               "{}, {})",
                                               camera_up.x(), camera_up.y(), camera_up.z()));
  }
  CheckThat(rest_fraction > 0 && rest_fraction <= 1, "rest_fraction",
            "a share of the frames in (0, 1]", rest_fraction);
}

const char* ToString(DeflectionStatus status) {
  switch (status) {
    case DeflectionStatus::kOk:
      return "ok";
    case DeflectionStatus::kMissingTrajectory:
      return "missing_trajectory";
    case DeflectionStatus::kTooFewFrames:
      return "too_few_frames";
    case DeflectionStatus::kNoRestPose:
      return "no_rest_pose";
    case DeflectionStatus::kCoincidentMarkers:
      return "coincident_markers";
  }
  return "?";
}

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
  options.Validate();
  const FrameRange range = RangeOf(t, first_frame, end_frame, options);
  std::vector<DeflectionSignal> out;
  for (const DeflectionLink& link : links) {
    DeflectionSignal d = UnusableLink(t, link, range);
    if (d.ok()) {
      d = link.is_root() ? RootDisplacement(link, *t.Find(link.child), range)
                         : RelativeAngle(t, link, range, options);
    }
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace simtree::identification
