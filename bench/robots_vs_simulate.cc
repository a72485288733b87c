// MuJoCo's pull-and-release of an exported tree beside simtree's own modal simulation of the
// same pull (issue 26 part 3): the pulled branch's tip in both over 5 s after the release, one
// CSV (time, simulate xyz, MuJoCo xyz) per branch, and the normalised RMSE (RMSE of the
// displacement from rest over the range of simulate's displacement along the pull).
//   build/bin/bench_robots_vs_simulate [branch ...] (default 6 1) > nrmse.txt
// The CSVs go to /tmp/simtree_robots_vs_simulate_b<id>.csv.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/tree_file.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/robots/export_robot.h"
#include "simtree/robots/mujoco_pull.h"

namespace {

constexpr double kHold = 0.5, kRelease = 1.5, kAfter = 5.0, kRate = 100.0;

class TipRecorder : public simtree::dynamics::FrameRecorder {
 public:
  TipRecorder(int branch, double arc) : branch_(branch), arc_(arc) {}
  void Record(int, double, const simtree::dynamics::TreeDynamics& sim) override {
    positions.push_back(sim.PointPosition(branch_, arc_));
  }
  std::vector<Eigen::Vector3d> positions;

 private:
  int branch_;
  double arc_;
};

void CompareBranch(const simtree::Tree& tree, const std::filesystem::path& xml, int branch) {
  const simtree::Branch& b = tree.branches[branch];
  const Eigen::Vector3d tip = b.tip().position;
  const Eigen::Vector3d direction = b.frame.u;
  simtree::dynamics::SimulationOptions sim;
  sim.duration_s = kRelease + kAfter;
  sim.fps = kRate;
  simtree::dynamics::PullSchedule pull;
  pull.rope.branch = branch;
  pull.rope.anchor = tip + 1000.0 * direction;  // far: a force of fixed direction, as in MuJoCo
  pull.rope.mode = simtree::dynamics::Rope::Mode::kDisplacement;
  pull.rope.displacement_m = 0.03 * b.Length();
  pull.hold_s = kHold;
  pull.release_s = kRelease;
  sim.pull = pull;
  TipRecorder recorder(branch, b.Length());
  simtree::dynamics::FrameRecorder* recorders[] = {&recorder};
  const auto modal = simtree::dynamics::RunSimulation(tree, sim, recorders);

  // The same pull is the same displacement (a pull test pulls "by 3%"): the export's masses come
  // from the wood density, not from the modal model's, so the same force would bend it
  // differently. A weak probe finds MuJoCo's compliance along the pull, then the force that
  // displaces its tip as far as simulate's.
  simtree::robots::MujocoPullOptions mj;
  mj.pull_site = fmt::format("tip_b{}", branch);
  mj.force = 0.01 * modal.pull_tension_n * direction;
  mj.hold_s = kHold;
  mj.release_s = kRelease;
  mj.duration_s = kRelease + kAfter;
  mj.sample_hz = kRate;
  mj.record_sites = {mj.pull_site};
  const auto probe = simtree::robots::RunMujocoPull(xml, mj);
  // Mean displacement along the pull over the hold (both still ring while held).
  const auto mean_shift = [&](const std::vector<Eigen::Vector3d>& track) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < track.size() && i < probe.times.size(); ++i) {
      if (probe.times[i] < kHold || probe.times[i] >= kRelease) continue;
      sum += (track[i] - track[0]).dot(direction);
      ++n;
    }
    return sum / std::max(n, 1);
  };
  const double probe_shift = mean_shift(probe.positions[0]);
  const double modal_shift = mean_shift(recorder.positions);
  mj.force *= modal_shift / probe_shift;
  const auto run = simtree::robots::RunMujocoPull(xml, mj);

  std::ofstream csv(fmt::format("/tmp/simtree_robots_vs_simulate_b{}.csv", branch));
  csv << "t,sim_x,sim_y,sim_z,mujoco_x,mujoco_y,mujoco_z\n";
  double sum2 = 0.0, lo = 1e9, hi = -1e9;
  int n = 0;
  const size_t count = std::min(recorder.positions.size(), run.times.size());
  for (size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d s = recorder.positions[i] - recorder.positions[0];
    const Eigen::Vector3d m = run.positions[0][i] - run.positions[0][0];
    csv << fmt::format("{:.3f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n", run.times[i], s.x(),
                       s.y(), s.z(), m.x(), m.y(), m.z());
    if (run.times[i] < kRelease) continue;
    sum2 += (s - m).squaredNorm();
    lo = std::min(lo, s.dot(direction));
    hi = std::max(hi, s.dot(direction));
    ++n;
  }
  const double nrmse = std::sqrt(sum2 / std::max(n, 1)) / (hi - lo);
  fmt::print(
      "branch {} pulled {:.3f} m: simulate {:.2f} N, MuJoCo {:.2f} N; NRMSE over {} s after the "
      "release {:.3f}\n",
      branch, modal_shift, modal.pull_tension_n, mj.force.norm(), kAfter, nrmse);
}

}  // namespace

int main(int argc, char** argv) {
  simtree::TreeFileOptions file;
  const std::string data = SIMTREE_SHARED_DATA_DIR;
  file.legacy_parameters = data + "/authors-demo/tree_parameters.txt";
  const simtree::Tree tree =
      simtree::ReadTreeFile(data + "/authors-demo/tree_model/tree01.txt", file);
  simtree::robots::ExportOptions options;
  options.calibration.time_step_s = 0.001;
  const auto xml = std::filesystem::temp_directory_path() / "simtree_robots_vs_simulate.xml";
  simtree::robots::ExportRobot(tree, options, xml, "tree01");
  std::vector<int> branches;
  for (int i = 1; i < argc; ++i) branches.push_back(std::stoi(argv[i]));
  if (branches.empty()) branches = {6, 1};
  for (int branch : branches) CompareBranch(tree, xml, branch);
  return 0;
}
