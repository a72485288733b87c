// MJCF: the model as nested MuJoCo bodies (robot_formats.h).

#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "simtree/robots/detail/xml_text.h"
#include "simtree/robots/robot_formats.h"

namespace simtree::robots {
namespace {

using detail::Num;
using detail::Vec;

struct MjcfPrinter {
  const RobotModel& model;
  std::vector<std::vector<int>> children;
  std::vector<std::vector<int>> sites;
  std::ostringstream out;

  void Body(int id, int depth) {
    const Segment& s = model.segments[id];
    const std::string pad(2 * depth, ' ');
    const Eigen::Vector3d origin =
        s.parent >= 0 ? model.segments[s.parent].base : Eigen::Vector3d::Zero();
    const Eigen::Matrix3d& i = s.inertia;
    out << pad << fmt::format("<body name=\"{}\" pos=\"{}\">\n", s.name, Vec(s.base - origin));
    out << pad
        << fmt::format("  <inertial pos=\"{}\" mass=\"{}\" fullinertia=\"{} {} {} {} {} {}\"/>\n",
                       Vec(s.center_of_mass - s.base), Num(s.mass_kg), Num(i(0, 0)), Num(i(1, 1)),
                       Num(i(2, 2)), Num(i(0, 1)), Num(i(0, 2)), Num(i(1, 2)));
    for (const Hinge& h : s.hinges) {
      out << pad
          << fmt::format(
                 "  <joint name=\"{}\" axis=\"{}\" stiffness=\"{}\" damping=\"{}\" "
                 "springref=\"{}\"/>\n",
                 h.name, Vec(h.axis), Num(h.stiffness), Num(h.damping), Num(h.spring_reference));
    }
    out << pad
        << fmt::format("  <geom name=\"{}\" fromto=\"0 0 0 {}\" size=\"{}\"/>\n", s.name,
                       Vec(s.tip - s.base), Num(s.radius));
    for (int site_id : sites[id]) {
      const Site& site = model.sites[site_id];
      const char* cls = site.kind == Site::Kind::kMarker  ? "marker"
                        : site.kind == Site::Kind::kGrasp ? "grasp"
                                                          : "tip";
      out << pad
          << fmt::format("  <site name=\"{}\" class=\"{}\" pos=\"{}\"/>\n", site.name, cls,
                         Vec(site.position - s.base));
    }
    for (int child : children[id]) Body(child, depth + 1);
    out << pad << "</body>\n";
  }
};

}  // namespace

std::string WriteMjcf(const RobotModel& model) {
  MjcfPrinter p{model, {}, {}, {}};
  p.children.resize(model.segments.size());
  p.sites.resize(model.segments.size());
  std::vector<int> roots;
  for (size_t i = 0; i < model.segments.size(); ++i) {
    const int parent = model.segments[i].parent;
    (parent >= 0 ? p.children[parent] : roots).push_back(static_cast<int>(i));
  }
  for (size_t i = 0; i < model.sites.size(); ++i) {
    p.sites[model.sites[i].segment].push_back(static_cast<int>(i));
  }
  auto& out = p.out;
  out << fmt::format("<mujoco model=\"{}\">\n", model.name);
  out << "  <!-- simtree export: every branch a chain of capsules on bending hinges; stiffness "
         "and damping ring at the simulation-ready tree's frequencies and damping ratios; "
         "spring references hold the rest pose under gravity. -->\n";
  out << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  out << fmt::format("  <option timestep=\"{}\" gravity=\"0 0 {}\"/>\n", Num(model.time_step_s),
                     Num(-model.gravity));
  out << "  <default>\n";
  if (model.collidable) {
    out << "    <!-- Tree capsules touch nothing of their own (contype 2, conaffinity 0): give a "
           "robot's geoms conaffinity bit 2 to touch them. -->\n"
           "    <geom type=\"capsule\" contype=\"2\" conaffinity=\"0\" "
           "rgba=\"0.45 0.32 0.2 1\"/>\n";
  } else {
    out << "    <!-- Tree capsules touch nothing (contype 0, conaffinity 0: left out of collision "
           "detection); export with --collidable for a robot to touch them. -->\n"
           "    <geom type=\"capsule\" contype=\"0\" conaffinity=\"0\" "
           "rgba=\"0.45 0.32 0.2 1\"/>\n";
  }
  out << "    <joint type=\"hinge\"/>\n"
         "    <default class=\"marker\"><site size=\"0.015\" rgba=\"1 0 0 1\"/></default>\n"
         "    <default class=\"grasp\"><site size=\"0.01\" rgba=\"0 0.8 0 1\"/></default>\n"
         "    <default class=\"tip\"><site size=\"0.005\" rgba=\"0 0 1 0.5\"/></default>\n"
         "  </default>\n";
  out << "  <worldbody>\n";
  for (int root : roots) p.Body(root, 2);
  out << "  </worldbody>\n</mujoco>\n";
  return out.str();
}

}  // namespace simtree::robots
