// URDF: one continuous joint per hinge (robot_formats.h).

#include <sstream>
#include <string>

#include <fmt/format.h>

#include "simtree/robots/detail/xml_text.h"
#include "simtree/robots/robot_formats.h"

namespace simtree::robots {
namespace {

using detail::kHingeLinkInertia;
using detail::kHingeLinkMass;
using detail::Num;
using detail::Vec;

void UrdfInertial(std::ostringstream& out, const Eigen::Vector3d& com, double mass,
                  const Eigen::Matrix3d& i) {
  out << fmt::format(
      "    <inertial><origin xyz=\"{}\"/><mass value=\"{}\"/>"
      "<inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/></inertial>\n",
      Vec(com), Num(mass), Num(i(0, 0)), Num(i(0, 1)), Num(i(0, 2)), Num(i(1, 1)), Num(i(1, 2)),
      Num(i(2, 2)));
}

void SegmentLink(std::ostringstream& out, const Segment& s) {
  out << fmt::format("  <link name=\"{}\">\n", s.name);
  UrdfInertial(out, s.center_of_mass - s.base, s.mass_kg, s.inertia);
  const Eigen::Vector3d chord = s.tip - s.base;
  const std::string origin = fmt::format("<origin xyz=\"{}\" rpy=\"{}\"/>", Vec(0.5 * chord),
                                         Vec(detail::RpyFromZTo(chord)));
  const std::string cylinder = fmt::format(
      "<geometry><cylinder radius=\"{}\" length=\"{}\"/>"
      "</geometry>",
      Num(s.radius), Num(chord.norm()));
  out << "    <visual>" << origin << cylinder << "<material name=\"bark\"/></visual>\n";
  out << "    <collision>" << origin << cylinder << "</collision>\n";
  out << "  </link>\n";
}

}  // namespace

std::string WriteUrdf(const RobotModel& model) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n";
  out << fmt::format("<robot name=\"{}\">\n", model.name);
  out << "  <!-- simtree export: every branch a chain of links on bending joints. URDF joints "
         "have no springs: each joint's stiffness and spring reference are in a <gazebo> "
         "element below. -->\n";
  out << "  <material name=\"bark\"><color rgba=\"0.45 0.32 0.2 1\"/></material>\n";
  out << "  <link name=\"world\"/>\n";
  std::ostringstream gazebo;
  for (const Segment& s : model.segments) {
    const Eigen::Vector3d origin =
        s.parent >= 0 ? model.segments[s.parent].base : Eigen::Vector3d::Zero();
    std::string parent = s.parent >= 0 ? model.segments[s.parent].name : "world";
    Eigen::Vector3d offset = s.base - origin;
    for (size_t h = 0; h < s.hinges.size(); ++h) {
      const Hinge& hinge = s.hinges[h];
      const bool last = h + 1 == s.hinges.size();
      const std::string child = last ? s.name : hinge.name + "_link";
      if (!last) {
        out << fmt::format("  <link name=\"{}\">\n", child);
        UrdfInertial(out, Eigen::Vector3d::Zero(), kHingeLinkMass,
                     kHingeLinkInertia * Eigen::Matrix3d::Identity());
        out << "  </link>\n";
      } else {
        SegmentLink(out, s);
      }
      out << fmt::format(
          "  <joint name=\"{}\" type=\"continuous\"><parent link=\"{}\"/><child link=\"{}\"/>"
          "<origin xyz=\"{}\"/><axis xyz=\"{}\"/><dynamics damping=\"{}\" friction=\"0\"/>"
          "</joint>\n",
          hinge.name, parent, child, Vec(offset), Vec(hinge.axis), Num(hinge.damping));
      gazebo << fmt::format(
          "  <gazebo reference=\"{}\"><springStiffness>{}</springStiffness>"
          "<springReference>{}</springReference></gazebo>\n",
          hinge.name, Num(hinge.stiffness), Num(hinge.spring_reference));
      parent = child;
      offset.setZero();
    }
  }
  for (const Site& site : model.sites) {
    const Segment& s = model.segments[site.segment];
    out << fmt::format("  <link name=\"{}\"/>\n", site.name);
    out << fmt::format(
        "  <joint name=\"{}_joint\" type=\"fixed\"><parent link=\"{}\"/><child link=\"{}\"/>"
        "<origin xyz=\"{}\"/></joint>\n",
        site.name, s.name, site.name, Vec(site.position - s.base));
  }
  out << gazebo.str();
  out << "</robot>\n";
  return out.str();
}

}  // namespace simtree::robots
