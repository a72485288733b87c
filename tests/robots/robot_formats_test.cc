// The URDF parsed by urdfdom and the SDF by sdformat, with the same joints, values and sites as
// the model they were written from; the MJCF loaded by MuJoCo.

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <urdf_parser/urdf_parser.h>
#include <Eigen/Core>

#include <sdf/sdf.hh>

#include "robots/authors_tree.h"
#include "simtree/robots/export_robot.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

class RobotFormats : public ::testing::Test {
 protected:
  void SetUp() override {
    tree_ = test::AuthorsTree01();
    options_.model.segments_per_branch = 3;
    model_ = MakeRobotModel(tree_, options_);
  }
  Tree tree_;
  ExportOptions options_;
  RobotModel model_;
};

TEST_F(RobotFormats, UrdfParsesWithTheSameJointValues) {
  const auto urdf = urdf::parseURDF(WriteUrdf(model_));
  ASSERT_TRUE(urdf) << "urdfdom refused the URDF";
  int checked = 0;
  for (const Segment& s : model_.segments) {
    for (const Hinge& h : s.hinges) {
      const auto joint = urdf->getJoint(h.name);
      ASSERT_TRUE(joint) << h.name;
      EXPECT_EQ(joint->type, urdf::Joint::CONTINUOUS);
      ASSERT_TRUE(joint->dynamics);
      EXPECT_NEAR(joint->dynamics->damping, h.damping, 1e-9 * h.damping);
      EXPECT_NEAR(joint->axis.x, h.axis.x(), 1e-9);
      EXPECT_NEAR(joint->axis.y, h.axis.y(), 1e-9);
      EXPECT_NEAR(joint->axis.z, h.axis.z(), 1e-9);
      ++checked;
    }
    const auto link = urdf->getLink(s.name);
    ASSERT_TRUE(link && link->inertial) << s.name;
    EXPECT_NEAR(link->inertial->mass, s.mass_kg, 1e-9 * s.mass_kg);
  }
  EXPECT_EQ(checked, model_.HingeCount());
  EXPECT_EQ(urdf->getRoot()->name, "world");
  for (const Site& site : model_.sites) EXPECT_TRUE(urdf->getLink(site.name)) << site.name;
}

TEST_F(RobotFormats, SdfParsesWithTheSameJointValues) {
  sdf::Root root;
  const sdf::Errors errors = root.LoadSdfString(WriteSdf(model_));
  for (const auto& e : errors) ADD_FAILURE() << e.Message();
  ASSERT_TRUE(errors.empty());
  const sdf::Model* sdf_model = root.Model();
  ASSERT_NE(sdf_model, nullptr);
  EXPECT_EQ(static_cast<int>(sdf_model->JointCount()), model_.HingeCount());
  for (const Segment& s : model_.segments) {
    for (const Hinge& h : s.hinges) {
      const sdf::Joint* joint = sdf_model->JointByName(h.name);
      ASSERT_NE(joint, nullptr) << h.name;
      const sdf::JointAxis* axis = joint->Axis(0);
      ASSERT_NE(axis, nullptr);
      EXPECT_NEAR(axis->Damping(), h.damping, 1e-9 * h.damping);
      EXPECT_NEAR(axis->SpringStiffness(), h.stiffness, 1e-9 * h.stiffness);
      EXPECT_NEAR(axis->SpringReference(), h.spring_reference,
                  1e-9 * std::abs(h.spring_reference) + 1e-15);
    }
    const sdf::Link* link = sdf_model->LinkByName(s.name);
    ASSERT_NE(link, nullptr) << s.name;
    EXPECT_NEAR(link->Inertial().MassMatrix().Mass(), s.mass_kg, 1e-9 * s.mass_kg);
  }
  for (const Site& site : model_.sites) EXPECT_TRUE(sdf_model->FrameNameExists(site.name));
}

TEST_F(RobotFormats, MjcfLoadsInMujocoWithTheSameJointValues) {
  const auto path = test::TempDir() / "tree.xml";
  test::WriteText(path, WriteMjcf(model_));
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  EXPECT_EQ(m->njnt, model_.HingeCount());
  EXPECT_EQ(m->nbody, static_cast<int>(model_.segments.size()) + 1);  // + the world
  EXPECT_EQ(m->nsite, static_cast<int>(model_.sites.size()));
  EXPECT_NEAR(m->opt.timestep, model_.time_step_s, 1e-9 * model_.time_step_s);
  for (const Segment& s : model_.segments) {
    for (const Hinge& h : s.hinges) {
      const int j = mj_name2id(m, mjOBJ_JOINT, h.name.c_str());
      ASSERT_GE(j, 0) << h.name;
      EXPECT_NEAR(m->jnt_stiffness[j], h.stiffness, 1e-8 * h.stiffness);
      EXPECT_NEAR(m->dof_damping[m->jnt_dofadr[j]], h.damping, 1e-8 * h.damping);
      EXPECT_NEAR(m->qpos_spring[m->jnt_qposadr[j]], h.spring_reference,
                  1e-8 * std::abs(h.spring_reference) + 1e-15);
    }
    const int b = mj_name2id(m, mjOBJ_BODY, s.name.c_str());
    ASSERT_GE(b, 0);
    EXPECT_NEAR(m->body_mass[b], s.mass_kg, 1e-8 * s.mass_kg);
  }
  mj_deleteModel(m);
}

// Under gravity the spring references hold the scanned pose: one simulated second moves no
// tip by more than a millimetre.
TEST_F(RobotFormats, MjcfHoldsTheScannedPoseUnderGravity) {
  const auto path = test::TempDir() / "tree.xml";
  test::WriteText(path, WriteMjcf(model_));
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  ASSERT_NEAR(m->opt.gravity[2], -9.81, 1e-9);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  std::vector<double> rest(d->site_xpos, d->site_xpos + 3 * m->nsite);
  const int steps = static_cast<int>(1.0 / m->opt.timestep);
  for (int i = 0; i < steps; ++i) mj_step(m, d);
  double largest = 0.0;
  for (int i = 0; i < 3 * m->nsite; ++i) {
    largest = std::max(largest, std::abs(d->site_xpos[i] - rest[i]));
  }
  EXPECT_LT(largest, 1e-3);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// docs/robots/scene.xml: the tree included beside a box gripper on a slide joint; driven to its
// end, the box meets branch 1 and bends the tree, and the simulation stays stable.
TEST_F(RobotFormats, ExampleSceneGripperPushesTheTree) {
  const auto dir = test::TempDir();
  RobotModel touchable = model_;
  touchable.collidable = true;  // export --collidable
  test::WriteText(dir / "tree.xml", WriteMjcf(touchable));
  std::filesystem::copy_file(std::filesystem::path(SIMTREE_SOURCE_DIR) / "docs/robots/scene.xml",
                             dir / "scene.xml");
  char error[1000] = "";
  mjModel* m = mj_loadXML((dir / "scene.xml").c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  const int slide = mj_name2id(m, mjOBJ_JOINT, "slide");
  const int pad = mj_name2id(m, mjOBJ_GEOM, "pad");
  ASSERT_GE(slide, 0);
  ASSERT_GE(pad, 0);
  ASSERT_EQ(m->nu, 1);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const std::vector<mjtNum> rest(d->site_xpos, d->site_xpos + 3 * m->nsite);
  d->ctrl[0] = m->actuator_ctrlrange[1];
  while (d->time < 1.0) mj_step(m, d);
  EXPECT_EQ(d->warning[mjWARN_BADQACC].number, 0) << "the simulation went unstable";
  EXPECT_GT(d->qpos[m->jnt_qposadr[slide]], 0.3) << "the box did not slide";
  int tree_contacts = 0;
  for (int c = 0; c < d->ncon; ++c) {
    const int other = d->contact[c].geom1 == pad ? d->contact[c].geom2 : d->contact[c].geom1;
    if ((d->contact[c].geom1 == pad || d->contact[c].geom2 == pad) &&
        std::string(mj_id2name(m, mjOBJ_GEOM, other)).rfind("b", 0) == 0) {
      ++tree_contacts;
    }
  }
  EXPECT_GT(tree_contacts, 0) << "the box does not touch the tree";
  double largest = 0.0;
  for (int s = 0; s < m->nsite; ++s) {
    largest = std::max(largest, (Eigen::Map<const Eigen::Vector3d>(d->site_xpos + 3 * s) -
                                 Eigen::Map<const Eigen::Vector3d>(rest.data() + 3 * s))
                                    .norm());
  }
  EXPECT_GT(largest, 0.05) << "the push did not bend the tree";
  mj_deleteData(d);
  mj_deleteModel(m);
}

// The tree's capsules are left out of collision detection unless asked (--collidable): then a
// robot geom with conaffinity bit 2 meets them.
TEST_F(RobotFormats, MjcfCapsulesCollideOnlyWhenAsked) {
  for (bool collidable : {false, true}) {
    RobotModel model = model_;
    model.collidable = collidable;
    const auto xml = test::TempDir() / "collide.xml";
    test::WriteText(xml, WriteMjcf(model));
    char error[1000] = "";
    mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    ASSERT_NE(m, nullptr) << error;
    ASSERT_EQ(m->ngeom, static_cast<int>(model.segments.size()));
    for (int g = 0; g < m->ngeom; ++g) {
      EXPECT_EQ(m->geom_contype[g], collidable ? 2 : 0) << g;
      EXPECT_EQ(m->geom_conaffinity[g], 0) << g;
    }
    mj_deleteModel(m);
  }
}

}  // namespace
}  // namespace simtree::robots
