#pragma once
// Stand-in views for the registration tests (stand_in_scene.h): the authors' tree01 seen from a
// ring of cameras, preprocessed and prepared, with their true poses.

#include <vector>

#include "simtree/eval/registration_metrics.h"
#include "simtree/preprocessing/depth_to_cloud.h"
#include "simtree/preprocessing/preprocess_view.h"
#include "simtree/registration/registration_view.h"
#include "stand_in_scene.h"
#include "test_util.h"

namespace simtree::test {

struct StandInViews {
  Tree tree;
  std::vector<ViewPose> poses;
  std::vector<registration::RegistrationView> views;
  std::vector<Eigen::Vector3d> tree_points;
};

inline StandInViews MakeStandInViews(int views, double step_deg, uint64_t seed,
                                     const registration::RegistrationViewOptions& options = {},
                                     const std::string& tree_file = "tree01.txt") {
  StandInViews out;
  out.tree = LoadDemoTree(SharedData("authors-demo/tree_model/" + tree_file));
  out.tree_points = eval::TreeSamplePoints(out.tree);
  StandInOptions scene;
  scene.views = views;
  scene.angle_step_deg = step_deg;
  scene.seed = seed;
  Eigen::Vector3d lo, hi;
  out.tree.Bounds(&lo, &hi);
  out.poses = StandInPoses(hi.z(), scene);
  for (size_t v = 0; v < out.poses.size(); ++v) {
    const RgbdImage image =
        RenderStandInView(out.tree, out.poses[v].world_from_camera, scene, seed * 1000 + v);
    const preprocessing::PreprocessResult pre =
        preprocessing::PreprocessView(preprocessing::DepthToCloud(image), {}, out.poses[v].name);
    out.views.push_back(registration::PrepareView(out.poses[v].name, pre, options));
  }
  return out;
}

}  // namespace simtree::test
