// SDF 1.9: links and revolute joints with springs (robot_formats.h).

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

void SdfInertial(std::ostringstream& out, const Eigen::Vector3d& com, double mass,
                 const Eigen::Matrix3d& i) {
  out << fmt::format(
      "      <inertial><pose>{} 0 0 0</pose><mass>{}</mass><inertia><ixx>{}</ixx><ixy>{}</ixy>"
      "<ixz>{}</ixz><iyy>{}</iyy><iyz>{}</iyz><izz>{}</izz></inertia></inertial>\n",
      Vec(com), Num(mass), Num(i(0, 0)), Num(i(0, 1)), Num(i(0, 2)), Num(i(1, 1)), Num(i(1, 2)),
      Num(i(2, 2)));
}

}  // namespace

std::string WriteSdf(const RobotModel& model) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n";
  out << fmt::format("  <model name=\"{}\">\n", model.name);
  out << "    <!-- simtree export: every branch a chain of links on bending joints with springs "
         "and dampers; link poses are in the model frame, all parallel to it. -->\n";
  for (const Segment& s : model.segments) {
    std::string parent = s.parent >= 0 ? model.segments[s.parent].name : "world";
    for (size_t h = 0; h < s.hinges.size(); ++h) {
      const Hinge& hinge = s.hinges[h];
      const bool last = h + 1 == s.hinges.size();
      const std::string child = last ? s.name : hinge.name + "_link";
      out << fmt::format("    <link name=\"{}\">\n      <pose>{} 0 0 0</pose>\n", child,
                         Vec(s.base));
      if (!last) {
        SdfInertial(out, Eigen::Vector3d::Zero(), kHingeLinkMass,
                    kHingeLinkInertia * Eigen::Matrix3d::Identity());
      } else {
        SdfInertial(out, s.center_of_mass - s.base, s.mass_kg, s.inertia);
        const Eigen::Vector3d chord = s.tip - s.base;
        const std::string shape = fmt::format(
            "<pose>{} {}</pose><geometry><capsule><radius>{}</radius><length>{}</length>"
            "</capsule></geometry>",
            Vec(0.5 * chord), Vec(detail::RpyFromZTo(chord)), Num(s.radius), Num(chord.norm()));
        out << "      <collision name=\"collision\">" << shape << "</collision>\n";
        out << "      <visual name=\"visual\">" << shape
            << "<material><diffuse>0.45 0.32 0.2 1</diffuse></material></visual>\n";
      }
      out << "    </link>\n";
      out << fmt::format(
          "    <joint name=\"{}\" type=\"revolute\"><parent>{}</parent><child>{}</child>"
          "<axis><xyz>{}</xyz><limit><lower>-1e16</lower><upper>1e16</upper></limit>"
          "<dynamics><damping>{}</damping><friction>0</friction>"
          "<spring_reference>{}</spring_reference><spring_stiffness>{}</spring_stiffness>"
          "</dynamics></axis></joint>\n",
          hinge.name, parent, child, Vec(hinge.axis), Num(hinge.damping),
          Num(hinge.spring_reference), Num(hinge.stiffness));
      parent = child;
    }
  }
  for (const Site& site : model.sites) {
    const Segment& s = model.segments[site.segment];
    out << fmt::format(
        "    <frame name=\"{}\" attached_to=\"{}\"><pose relative_to=\"{}\">{} 0 0 0</pose>"
        "</frame>\n",
        site.name, s.name, s.name, Vec(site.position - s.base));
  }
  out << "  </model>\n</sdf>\n";
  return out.str();
}

}  // namespace simtree::robots
