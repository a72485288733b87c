#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/tree_file.h"
#include "simtree/robots/export_robot.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterExport(CLI::App& app) {
  struct Args {
    std::string input, output, parameters, format = "mjcf", twist = "auto";
    TreeFileOptions tree_options;
    robots::ExportOptions options;
    bool no_gravity = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "export",
      "Simulation-ready tree -> robot simulator model: MJCF (MuJoCo), URDF or SDF. Every branch "
      "a chain of capsule links (masses from the wood density and volume) on two bending hinges "
      "per segment (+ a twist hinge on branches that carry others), the trunk's base fixed to "
      "the world. Hinge stiffness and damping make each branch, with the sub-tree riding on it, "
      "ring at its material's bending frequencies and damping ratios (its parent held still); "
      "spring references hold the scanned pose under gravity. Sites (URDF: fixed links, SDF: "
      "frames): marker_<id> at every tape marker, grasp_b<id> midway along every branch, "
      "tip_b<id> at every tip. Kept: geometry as capsules, hierarchy, each branch's first "
      "bending modes and damping, two-way coupling (a swinging child now shakes its parent). "
      "Lost: the modal model's exact one-mode shapes and one-way coupling, the demo's mode "
      "spread; URDF has no joint springs (in <gazebo> elements). Units: metres, kilograms, "
      "seconds, radians; N m/rad, N m s/rad. See docs/robots.md");
  verb->add_option("tree", args->input,
                   "Simulation-ready tree: .json (simtree build) or .txt (authors' format, "
                   "with --params)")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args->output, "Model file to write (.xml, .urdf, .sdf)")->required();
  verb->add_option("--format", args->format, "mjcf, urdf or sdf")->capture_default_str();
  CLI::Option* segments =
      verb->add_option("--segments-per-branch", args->options.model.segments_per_branch,
                       "Rigid segments per branch (each with its hinges). Unless given, the step "
                       "budget may lower it for a large tree")
          ->capture_default_str()
          ->check(CLI::PositiveNumber);
  verb->add_option("--min-steps-per-second", args->options.budget.min_steps_per_second,
                   "Step budget: a tree whose MuJoCo step is estimated slower (on the 2-core "
                   "machine of docs/benchmarks.md) gets fewer segments per branch, then no twist "
                   "hinges, unless --segments-per-branch / --twist were given; 0 = no budget")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--max-bodies", args->options.model.max_bodies,
                   "Tree-wide budget of segments: more branches than budget/segments get fewer "
                   "segments each (at least 1); 0 = none")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  CLI::Option* twist = verb->add_option(
      "--twist", args->twist,
      "Twist hinges: none, auto (branches that carry others) or all. Unless given, the step "
      "budget may drop them for a large tree");
  twist->capture_default_str();
  verb->add_flag("--collidable", args->options.model.collidable,
                 "MJCF: a robot's geoms with conaffinity bit 2 can touch the tree's capsules "
                 "(contype 2); without it the capsules are left out of collision detection");
  verb->add_option("--density", args->options.model.wood_density_kg_m3,
                   "Wood density (kg/m^3) for the segment masses")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_option("--stiffness-exponent", args->options.calibration.stiffness_exponent,
                   "Hinge stiffness along a branch as (r/r_base)^exponent: 0 a uniform beam "
                   "(as the modal model's mode shape), 4 a tapered beam of one wood")
      ->capture_default_str();
  verb->add_option("--time-step", args->options.calibration.time_step_s,
                   "MuJoCo step written in the MJCF (s); 0 = from the stiffest chain mode")
      ->capture_default_str();
  verb->add_flag("--no-gravity", args->no_gravity,
                 "Spring references at 0 and MJCF gravity off (default: gravity on, the springs "
                 "hold the scanned pose under it)");
  AddTreeFileOptions(verb, args->tree_options, args->parameters);
  verb->footer(Examples({
      "simtree export simready.json --format mjcf --out tree.xml",
      "simtree export simready.json --format urdf --out tree.urdf --segments-per-branch 2",
      "simtree export simready.json --format sdf --out tree.sdf --twist none",
      "simtree export big.json --out big.xml --min-steps-per-second 0   # no step budget",
      "simtree export tree01.txt --params tree_parameters.txt --out tree01.xml",
  }));
  verb->callback([args, segments, twist] {
    FinishTreeFileOptions(args->tree_options, args->parameters);
    args->options.format = robots::ParseRobotFormat(args->format);
    args->options.model.twist = robots::ParseTwistHinges(args->twist);
    // What the user chose, the budget keeps.
    args->options.budget.fixed_segments = segments->count() > 0;
    args->options.budget.fixed_twist = twist->count() > 0;
    if (args->no_gravity) args->options.calibration.gravity = 0.0;
    RefuseToOverwriteInputs(args->output, {args->input, args->parameters});
    const Tree tree = ReadTreeFile(args->input, args->tree_options);
    const robots::ExportResult result =
        robots::ExportRobot(tree, args->options, args->output, args->input);
    std::printf(
        "%s: %d branches, %d bodies (%d per branch), %d hinges, %d sites, %.2f kg, "
        "step %.3g s\n",
        robots::ToString(args->options.format), result.branches, result.bodies,
        result.segments_per_branch, result.hinges, result.sites, result.total_mass_kg,
        result.time_step_s);
    std::printf("step budget: %s\n", result.budget.Summary().c_str());
    const robots::CalibrationReport& calibration = result.calibration;
    if (calibration.gravity_stiffened_hinges > 0) {
      std::printf("gravity: %d hinges stiffened (up to +%.0f%%) so the whole tree stands\n",
                  calibration.gravity_stiffened_hinges, 100 * calibration.gravity_largest_raise);
    }
    std::fflush(stdout);  // before the warning on stderr
    if (result.budget.over_budget) {
      spdlog::warn(
          "the model is estimated to step slower than --min-steps-per-second {:.0f} at what "
          "--segments-per-branch / --twist allow: fewer segments, --twist none or leaving them "
          "to the budget would be faster",
          args->options.budget.min_steps_per_second);
    }
    spdlog::info("wrote {}", args->output);
  });
}

}  // namespace simtree::cli
