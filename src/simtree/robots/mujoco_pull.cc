#include "simtree/robots/mujoco_pull.h"

#include <chrono>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/identification/estimators.h"

namespace simtree::robots {
namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

double Smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

double ForceFactor(const MujocoPullOptions& o, double t) {
  if (t >= o.release_s) return 0.0;
  if (o.hold_s <= 0) return 1.0;
  return Smoothstep(t / o.hold_s);
}

int SiteId(const mjModel* m, const std::string& name, const std::filesystem::path& file) {
  const int id = mj_name2id(m, mjOBJ_SITE, name.c_str());
  if (id < 0) throw InputError(file.string(), name, "no such site in the model");
  return id;
}

}  // namespace

void MujocoPullOptions::Validate() const {
  CheckOption(!pull_site.empty(), "mujoco pull", "pull_site", "expected a site name");
  CheckOption(force.allFinite(), "mujoco pull", "force", "expected a finite force");
  CheckNonNegative("hold_s", hold_s);
  CheckAtLeast("release_s", release_s, hold_s);
  CheckPositive("duration_s", duration_s);
  CheckPositive("sample_hz", sample_hz);
}

MujocoPullResult RunMujocoPull(const std::filesystem::path& mjcf,
                               const MujocoPullOptions& options) {
  options.Validate();
  char error[1000] = "";
  std::unique_ptr<mjModel, ModelDeleter> model(
      mj_loadXML(mjcf.c_str(), nullptr, error, sizeof(error)));
  if (!model) throw InputError(mjcf.string(), "", std::string("MuJoCo refused it: ") + error);
  std::unique_ptr<mjData, DataDeleter> data(mj_makeData(model.get()));
  mjModel* m = model.get();
  mjData* d = data.get();
  const int pull_site = SiteId(m, options.pull_site, mjcf);
  const int pull_body = m->site_bodyid[pull_site];
  std::vector<int> sites;
  for (const std::string& name : options.record_sites) sites.push_back(SiteId(m, name, mjcf));

  MujocoPullResult out;
  out.time_step_s = m->opt.timestep;
  out.release_s = options.release_s;
  out.positions.resize(sites.size());
  mj_forward(m, d);
  const auto record = [&] {
    out.times.push_back(d->time);
    for (size_t i = 0; i < sites.size(); ++i) {
      const mjtNum* p = d->site_xpos + 3 * sites[i];
      out.positions[i].emplace_back(p[0], p[1], p[2]);
    }
  };
  record();
  const int64_t steps = std::llround(options.duration_s / m->opt.timestep);
  const double sample_dt = 1.0 / options.sample_hz;
  double next_sample = sample_dt;
  const auto start = std::chrono::steady_clock::now();
  for (int64_t step = 0; step < steps; ++step) {
    // The force acts at the site: xfrc_applied acts at the body's centre of mass, so add the
    // moment of the offset.
    mju_zero(d->xfrc_applied + 6 * pull_body, 6);
    const Eigen::Vector3d force = ForceFactor(options, d->time) * options.force;
    if (force.squaredNorm() > 0) {
      const Eigen::Vector3d arm =
          Eigen::Vector3d(d->site_xpos + 3 * pull_site) - Eigen::Vector3d(d->xipos + 3 * pull_body);
      const Eigen::Vector3d torque = arm.cross(force);
      for (int k = 0; k < 3; ++k) {
        d->xfrc_applied[6 * pull_body + k] = force[k];
        d->xfrc_applied[6 * pull_body + 3 + k] = torque[k];
      }
    }
    mj_step(m, d);
    if (d->time >= next_sample - 1e-9) {
      record();
      next_sample += sample_dt;
    }
  }
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.steps = steps;
  for (int i = 0; i < m->nq; ++i) {
    if (!std::isfinite(d->qpos[i])) {
      throw Error(fmt::format("{}: the MuJoCo simulation went unstable (step {} s)", mjcf.string(),
                              m->opt.timestep));
    }
  }
  return out;
}

Ringing MeasureRinging(const MujocoPullResult& run, int site, double delay_s) {
  Ringing out;
  const auto& track = run.positions.at(site);
  size_t first = 0;
  while (first < run.times.size() && run.times[first] < run.release_s + delay_s) ++first;
  if (run.times.size() < first + 20) {
    out.message = "fewer than 20 samples after the release";
    return out;
  }
  identification::SampledSignal signal;
  signal.start_time_s = run.times[first];
  signal.dt = run.times[first + 1] - run.times[first];
  const int n = static_cast<int>(run.times.size() - first);
  signal.values.resize(n, 3);
  signal.valid.assign(n, true);
  signal.channel_names = {"x", "y", "z"};
  for (int i = 0; i < n; ++i) {
    signal.values.row(i) = (track[first + i] - track.front()).transpose();
  }
  const auto estimate =
      identification::EstimateModes(signal, identification::EstimatorKind::kDampedSinusoidFit);
  out.ok = estimate.dominant.has_frequency() && estimate.dominant.has_damping();
  out.message = estimate.dominant.message;
  out.frequency_hz = estimate.dominant.frequency_hz;
  out.damping_ratio = estimate.dominant.damping_ratio;
  out.amplitude_m = estimate.dominant.amplitude;
  return out;
}

}  // namespace simtree::robots
