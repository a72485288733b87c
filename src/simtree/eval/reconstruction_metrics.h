#pragma once
// Scores of a static reconstruction.
//
// Against a true tree (synth's gt/tree.json, or the tree a stand-in scan was sampled from):
//  - branch recall: a true branch (base radius >= min_true_radius_m) is found when more than
//    `found_share` of its length lies near the reconstructed skeleton: within near_distance_m plus
//    the true radius there (a skeleton anywhere inside the wood is on the branch);
//  - branch precision: a reconstructed branch is correct when more than `found_share` of its
//    length lies near the true skeleton. Reconstructed branches that lie mostly along true
//    branches thinner than min_true_radius_m are not scored (finding a thin branch is not an
//    error, and missing one is not counted either);
//  - mean skeleton distance: the mean of (reconstructed skeleton to true skeleton) and (true
//    skeleton of scored branches to reconstructed skeleton), each a mean over 1 cm samples; also
//    with the true side over wood >= min_true_radius_m only (thick_skeleton_distance_m);
//  - radius error: mean |r - r_true| / r_true over samples of found scored branches, r from the
//    nearest reconstructed skeleton sample;
//  - trunk radius error: |mean reconstructed / mean true trunk radius - 1| over the lowest
//    `trunk_height_m` of the true trunk;
//  - total-length error: (reconstructed - true) / true length of wood at least min_true_radius_m
//    thick: true skeleton samples that thick, against reconstructed samples whose nearest true
//    wood is that thick or that lie near no true wood at all, on scored reconstructed branches
//    (a branch along thin true wood claims none, though it starts near the thick wood it leaves).
// Against the scan (real clouds): distance of every point from the model's surface (the union of
// the branches' frustums), its mean, median and the share within 2 cm; branch counts by level.

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::eval {

struct TruthScoreOptions {
  double min_true_radius_m = 0.01;  // metres: true branches with a thinner base are not scored
  double near_distance_m = 0.03;    // metres beyond the true radius that still count as near
  double found_share = 0.5;         // share of a branch's length near the other skeleton: found
  double sample_step_m = 0.01;      // metres between skeleton samples
  double trunk_height_m = 1.0;      // metres of the true trunk its radius is compared over

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct BranchMatch {
  int branch = 0;
  int level = 0;
  double length_m = 0.0;
  double base_radius_m = 0.0;
  double near_share = 0.0;  // share of its length near the other skeleton
  bool scored = false;
  bool found = false;  // true branch: found; reconstructed branch: correct
  int matched = -1;    // the other tree's branch most of it lies along (-1: none near)
};

struct TruthScores {
  int true_branches = 0, found = 0;  // scored true branches
  double recall = 0.0;
  int reconstructed_branches = 0, correct = 0;  // scored reconstructed branches
  double precision = 0.0;
  double reconstruction_to_truth_m = 0.0, truth_to_reconstruction_m = 0.0;
  double mean_skeleton_distance_m = 0.0;
  // The same with the true side only over wood at least min_true_radius_m thick: the thin ends
  // of scored branches, which a camera may not resolve at all, left out.
  double thick_truth_to_reconstruction_m = 0.0;
  double thick_skeleton_distance_m = 0.0;
  double radius_error = 0.0;
  double trunk_radius_m = 0.0, true_trunk_radius_m = 0.0, trunk_radius_error = 0.0;
  double length_m = 0.0, true_length_m = 0.0, length_error = 0.0;  // wood >= min radius
  double total_length_m = 0.0, true_total_length_m = 0.0;          // all wood
  std::vector<BranchMatch> truth, reconstruction;
};

TruthScores ScoreAgainstTruth(const Tree& reconstruction, const Tree& truth,
                              const TruthScoreOptions& options = {});

struct CloudFitScores {
  size_t points = 0;
  double mean_distance_m = 0.0;
  double median_distance_m = 0.0;
  double within_m = 0.02;
  double share_within = 0.0;  // of points within `within_m` of the surface
  int branches = 0;
  std::vector<int> branches_by_level;
  double total_length_m = 0.0;
};

CloudFitScores ScoreAgainstCloud(const Tree& reconstruction,
                                 std::span<const Eigen::Vector3d> points, double within_m = 0.02);

// Distance of each point from the model surface (the union of branch frustums).
std::vector<double> SurfaceDistances(const Tree& tree, std::span<const Eigen::Vector3d> points);

std::vector<int> BranchCountsByLevel(const Tree& tree);

std::string FormatTruthScores(const TruthScores& scores);
std::string FormatCloudFit(const CloudFitScores& scores);

}  // namespace simtree::eval
