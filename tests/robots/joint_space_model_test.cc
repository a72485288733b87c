// The linearisation the coupled tuning solves on, against MuJoCo's own: the joint-space mass
// matrix (mj_fullM at the rest pose) and gravity's stiffness (central differences of MuJoCo's
// gravity forces about the rest pose), on an exported three-branch tree with twist hinges.

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <Eigen/Geometry>

#include "simtree/core/frames.h"
#include "simtree/robots/detail/joint_space_model.h"
#include "simtree/robots/export_robot.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

Tree ThreeBranches() {
  Tree tree;
  Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.06},
                 {Eigen::Vector3d(0.03, 0, 0.7), 0.05},
                 {Eigen::Vector3d(0.05, 0.02, 1.4), 0.04}};
  tree.branches.push_back(trunk);
  for (int k = 0; k < 2; ++k) {
    Branch child;
    child.id = k + 1;
    child.parent = 0;
    child.parent_node = k + 1;
    const Eigen::Vector3d base = trunk.nodes[k + 1].position;
    const Eigen::Vector3d dir = Eigen::Vector3d(k ? -0.6 : 0.7, k ? 0.5 : -0.2, 0.6).normalized();
    child.nodes = {{base, 0.025}, {base + 0.4 * dir, 0.02}, {base + 0.8 * dir, 0.012}};
    tree.branches.push_back(child);
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  for (Branch& b : tree.branches) {
    b.material = Material::FromFrequencyDampingStiffness(
        b.is_trunk() ? 2.0 : 1.3, 0.03, b.is_trunk() ? 3000.0 : 60.0, MaterialSource::kAssumed);
  }
  return tree;
}

struct Loaded {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  ~Loaded() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
};

TEST(JointSpaceModel, MatchesMujocoMassAndGravityStiffness) {
  const Tree tree = ThreeBranches();
  ExportOptions options;
  options.model.segments_per_branch = 3;
  options.model.twist = TwistHinges::kAll;
  const RobotModel model = MakeRobotModel(tree, options);
  const auto xml = test::TempDir() / "three_branches.xml";
  test::WriteText(xml, WriteMjcf(model));
  Loaded mj;
  char error[1000] = "";
  mj.m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_TRUE(mj.m) << error;
  mj.d = mj_makeData(mj.m);
  const detail::JointSpaceModel lin = detail::LineariseRobotModel(model, model.gravity);
  const int n = static_cast<int>(lin.hinges.size());
  ASSERT_EQ(n, mj.m->nv);
  std::vector<int> dof(n);
  for (int i = 0; i < n; ++i) {
    const auto& h = model.segments[lin.hinges[i].segment].hinges[lin.hinges[i].hinge];
    const int joint = mj_name2id(mj.m, mjOBJ_JOINT, h.name.c_str());
    ASSERT_GE(joint, 0) << h.name;
    dof[i] = mj.m->jnt_dofadr[joint];
  }
  mj_forward(mj.m, mj.d);
  std::vector<mjtNum> full(n * n);
  mj_fullM(mj.m, full.data(), mj.d->qM);
  const double scale_m = lin.mass.cwiseAbs().maxCoeff();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      EXPECT_NEAR(lin.mass(i, j), full[dof[i] * n + dof[j]], 1e-6 * scale_m) << i << " " << j;
    }
  }
  // Gravity's stiffness: d(qfrc_bias)/dq at rest, zero velocity (bias = gravity's forces then).
  const double eps = 1e-6;
  const double scale_g = lin.gravity.cwiseAbs().maxCoeff();
  ASSERT_GT(scale_g, 0.0);
  for (int j = 0; j < n; ++j) {
    std::vector<mjtNum> plus(n), minus(n);
    for (double sign : {1.0, -1.0}) {
      mju_zero(mj.d->qpos, mj.m->nq);
      mj.d->qpos[dof[j]] = sign * eps;
      mj_forward(mj.m, mj.d);
      std::copy(mj.d->qfrc_bias, mj.d->qfrc_bias + n, sign > 0 ? plus.begin() : minus.begin());
    }
    for (int i = 0; i < n; ++i) {
      const double fd = (plus[dof[i]] - minus[dof[i]]) / (2 * eps);
      EXPECT_NEAR(lin.gravity(i, j), fd, 1e-4 * scale_g) << i << " " << j;
    }
  }
}

}  // namespace
}  // namespace simtree::robots
