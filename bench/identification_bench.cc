// Identification: how accurate each estimator is (tables, on records with known modes) and how
// fast (Google Benchmark timings). docs/identification.md and docs/benchmarks.md quote the
// output.
//
//   bench_identification --tables            accuracy tables only (Monte Carlo, seeded)
//   bench_identification                     timings only
//   bench_identification --independent [SEEDS]
//                                            independent-mode records (every link its own modes);
//                                            on stderr each link's errors, also in standard
//                                            deviations of its estimate
//   bench_identification --score SCENE MATERIALS [READY_TREE]
//                                            scores an identification of a synth scene against
//                                            SCENE/gt/modal.json (and a built tree's branches)

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/tree_json.h"
#include "simtree/eval/identification_metrics.h"
#include "simtree/identification/detail/test_signals.h"
#include "simtree/identification/estimators.h"
#include "simtree/identification/identify.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/ground_truth.h"
#include "simtree/tracking/tracker_error.h"

namespace simtree {
namespace {

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

// NOTES.md's half-power table: one mode, 30 fps, noise 5% of the initial amplitude.
void NotesTable() {
  struct Case {
    double f, zeta, duration;
  };
  std::printf(
      "### Half-power bandwidth on short records (mean of 50 seeds; 30 fps, 5%% noise)\n\n");
  std::printf(
      "| true f, zeta | record | half_power_fft zeta | interpolated_spectrum zeta | "
      "damped_sinusoid_fit zeta (mean predicted sd) | f: fft / interp / fit |\n");
  std::printf("| --- | --- | --- | --- | --- | --- |\n");
  for (const Case c :
       {Case{0.72, 0.022, 10}, Case{0.72, 0.022, 40}, Case{1.0, 0.03, 10}, Case{1.5, 0.06, 10}}) {
    double z[3] = {}, f[3] = {}, sd = 0;
    const int trials = 50;
    for (int seed = 1; seed <= trials; ++seed) {
      identification::DecayRecordOptions o;
      o.duration_s = c.duration;
      o.noise_std = 0.05;
      o.seed = seed;
      const identification::SampledSignal s =
          identification::MakeDecayRecord({{{c.f, c.zeta, 1.0, 0.4}}}, o);
      int k = 0;
      for (identification::EstimatorKind kind : identification::AllEstimators()) {
        const identification::ModalEstimate e = identification::EstimateModes(s, kind).dominant;
        z[k] += e.damping_ratio / trials;
        f[k] += e.frequency_hz / trials;
        if (kind == identification::EstimatorKind::kDampedSinusoidFit) sd += e.damping_std / trials;
        ++k;
      }
    }
    std::printf("| %.2f Hz, %.3f | %.0f s | %.4f | %.4f | %.4f (%.4f) | %.3f / %.3f / %.3f |\n",
                c.f, c.zeta, c.duration, z[0], z[1], z[2], sd, f[0], f[1], f[2]);
  }
  std::printf("\n");
}

// Tree-like records: two bending planes sharing a dominant mode (the second plane sometimes split
// a few percent from it, as in a real branch), one to three weaker modes of the tree, white noise
// and tracker gaps. Truth is the dominant mode.
struct Scenario {
  std::vector<std::vector<identification::DampedSinusoid>> channels;
  identification::DampedSinusoid dominant;
};

Scenario RandomScenario(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Scenario s;
  const double f = 0.7 + 0.9 * u(rng), zeta = 0.02 + 0.04 * u(rng);
  const double phase = 6.283 * u(rng);
  s.dominant = {f, zeta, 1.0, phase};
  s.channels.resize(2);
  s.channels[0].push_back(s.dominant);
  const double split = u(rng) < 0.5 ? 1.0 : 1.0 + 0.05 * (u(rng) - 0.5) * 2;
  s.channels[1].push_back(
      {f * split, zeta * (0.8 + 0.4 * u(rng)), 0.3 + 0.5 * u(rng), 6.283 * u(rng)});
  const int extra = 1 + static_cast<int>(3 * u(rng));
  for (int k = 0; k < extra; ++k) {
    const double fk = 0.6 + 2.4 * u(rng);
    if (std::abs(fk / f - 1) < 0.08) continue;  // a neighbour this close would be "the" mode
    const identification::DampedSinusoid m{fk, 0.02 + 0.05 * u(rng), 0.1 + 0.35 * u(rng),
                                           6.283 * u(rng)};
    s.channels[k % 2].push_back(m);
  }
  return s;
}

void ComparisonTable() {
  std::printf(
      "### Estimators on tree-like two-plane records (10 s, 30 fps, 1%% gaps; 200 "
      "records per row)\n\n");
  std::printf(
      "| noise (of dominant amplitude) | estimator | median abs df/f | 90th pct | median "
      "abs dzeta/zeta | 90th pct | no value | ms per record |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (double noise : {0.02, 0.05, 0.10, 0.20}) {
    for (identification::EstimatorKind kind : identification::AllEstimators()) {
      std::mt19937_64 rng(7);
      std::vector<double> df, dz;
      int failed = 0;
      double seconds = 0;
      const int records = 200;
      for (int r = 0; r < records; ++r) {
        const Scenario sc = RandomScenario(rng);
        identification::DecayRecordOptions o;
        o.noise_std = noise;
        o.gap_rate = 0.01;
        o.seed = 1000 + r;
        const identification::SampledSignal s = identification::MakeDecayRecord(sc.channels, o);
        const auto start = std::chrono::steady_clock::now();
        const identification::ModalEstimate e = identification::EstimateModes(s, kind).dominant;
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!e.has_frequency() || !e.has_damping()) {
          ++failed;
          continue;
        }
        df.push_back(std::abs(e.frequency_hz / sc.dominant.frequency_hz - 1));
        dz.push_back(std::abs(e.damping_ratio / sc.dominant.damping_ratio - 1));
      }
      std::printf("| %.0f%% | %s | %.2f%% | %.2f%% | %.1f%% | %.1f%% | %d | %.1f |\n", 100 * noise,
                  ToString(kind), 100 * Percentile(df, 0.5), 100 * Percentile(df, 0.9),
                  100 * Percentile(dz, 0.5), 100 * Percentile(dz, 0.9), failed,
                  1e3 * seconds / records);
    }
  }
  std::printf("\n");
}

// Independent-mode records (test_signals.h MakeIndependentModeTree: every link rings at its own
// two frequencies, children riding on their parents), a tracker's error added (2.5 mm, ~1% gaps,
// jumps), 10 s of free decay at 30 fps: the paper's half-power, the damped sinusoid fit per link,
// on the shared poles, and by the per-link choice (the default), scored against each link's
// dominant mode; "in 1 sd": share of links whose truth lies within the estimate's standard
// deviation. Rows in the table bench/identification_on_synth.sh prints for the FEM records.
void IndependentTable(int seeds) {
  struct Column {
    std::vector<double> df, dz;
    int links = 0, missing = 0, f_covered = 0, z_covered = 0, with_sd = 0, shared = 0;
  };
  const char* names[] = {"half_power_fft", "damped_sinusoid_fit (per link)",
                         "damped_sinusoid_fit (joint poles)", "damped_sinusoid_fit (choice)"};
  Column columns[4];
  for (int seed = 1; seed <= seeds; ++seed) {
    identification::IndependentTreeOptions tree_options;
    tree_options.seed = seed;
    std::vector<identification::DampedSinusoid> truth;
    const identification::SyntheticMarkerTree tree =
        identification::MakeIndependentModeTree(tree_options, 10.0, &truth);
    std::vector<MarkerLink> markers;
    tracking::TrackerErrorOptions error;
    error.seed = seed;
    const Trajectories tracks = tracking::SimulateTrackerError(
        identification::MakeMarkerTrajectories(tree, 30, 2, 10, &markers), error);
    identification::IdentifyOptions options;
    options.window_s = 10;
    const identification::IdentificationResult r =
        identification::IdentifyMaterials(tracks, markers, options);
    for (const identification::LinkIdentification& link : r.links) {
      const identification::DampedSinusoid& t = truth[link.deflection.link.child];
      const identification::SignalEstimate* hp =
          link.Find(identification::EstimatorKind::kHalfPowerFft);
      identification::ModalEstimate none;
      none.status = identification::EstimateStatus::kFailed;
      const identification::ModalEstimate values[4] = {hp ? hp->dominant : none, link.poles.own,
                                                       link.poles.joint, link.value};
      for (int c = 0; c < 4; ++c) {
        Column& col = columns[c];
        const identification::ModalEstimate& e = values[c];
        ++col.links;
        if (c == 3) col.shared += link.poles.shared;
        if (e.status != identification::EstimateStatus::kOk || !e.has_damping()) {
          ++col.missing;
          continue;
        }
        col.df.push_back(std::abs(e.frequency_hz / t.frequency_hz - 1));
        col.dz.push_back(std::abs(e.damping_ratio / t.damping_ratio - 1));
        if (std::isfinite(e.frequency_std_hz) && std::isfinite(e.damping_std)) {
          // Per link on stderr: truth's distance from the value in standard deviations.
          std::fprintf(stderr, "seed %d %s %s %s f %+.2f%% %+.2f sd, zeta %+.1f%% %+.2f sd\n", seed,
                       link.deflection.link.label.c_str(), names[c],
                       link.poles.shared ? "shared" : "own",
                       100 * (e.frequency_hz / t.frequency_hz - 1),
                       (e.frequency_hz - t.frequency_hz) / e.frequency_std_hz,
                       100 * (e.damping_ratio / t.damping_ratio - 1),
                       (e.damping_ratio - t.damping_ratio) / e.damping_std);
          ++col.with_sd;
          col.f_covered += std::abs(e.frequency_hz - t.frequency_hz) <= e.frequency_std_hz;
          col.z_covered += std::abs(e.damping_ratio - t.damping_ratio) <= e.damping_std;
        }
      }
    }
  }
  for (int c = 0; c < 4; ++c) {
    const Column& col = columns[c];
    const std::string cover =
        col.with_sd > 0 ? fmt::format("{:.0f}% / {:.0f}%", 100.0 * col.f_covered / col.with_sd,
                                      100.0 * col.z_covered / col.with_sd)
                        : "-";
    std::printf(
        "| independent modes, %d seeds | %s | 2.5 mm | %d | %d | %.2f%% | %.1f%% | %s |%s\n", seeds,
        names[c], col.links, col.missing, 100 * Percentile(col.df, 0.5),
        100 * Percentile(col.dz, 0.5), cover.c_str(),
        c == 3 ? fmt::format(" {} of {} links shared", col.shared, col.links).c_str() : "");
  }
}

int Score(const std::string& scene, const std::string& materials_path, const std::string& tree) {
  const ModalTruth truth = ReadModalTruth(scene + "/gt/modal.json");
  const identification::MaterialsFile materials = identification::ReadMaterialsJson(materials_path);
  std::printf("scene %s (truth: %s), %zu truth links, %zu truth branches\n", scene.c_str(),
              truth.source.c_str(), truth.links.size(), truth.branches.size());
  const eval::LinkScores chosen = eval::ScoreLinks(materials, truth);
  std::printf("%s", eval::FormatLinkScores(chosen).c_str());
  for (identification::EstimatorKind kind : identification::AllEstimators()) {
    std::printf(
        "%s\n",
        FormatSummary(ToString(kind), eval::ScoreLinks(materials, truth, kind).summary).c_str());
  }
  if (!tree.empty()) {
    const eval::BranchScores b = eval::ScoreBranches(ReadTreeJson(tree), truth);
    std::printf("%s\n", FormatSummary("branches measured", b.measured).c_str());
    std::printf("%s\n", FormatSummary("branches interpolated", b.interpolated).c_str());
  }
  return 0;
}

// Timings: each estimator on one tree-like record; a whole identification of a tree of 6 links
// and its root marker.
void BM_Estimator(benchmark::State& state) {
  const identification::EstimatorKind kind =
      static_cast<identification::EstimatorKind>(state.range(0));
  std::mt19937_64 rng(3);
  const Scenario sc = RandomScenario(rng);
  identification::DecayRecordOptions o;
  o.noise_std = 0.05;
  const identification::SampledSignal s = identification::MakeDecayRecord(sc.channels, o);
  for (auto _ : state) benchmark::DoNotOptimize(identification::EstimateModes(s, kind));
  state.SetLabel(ToString(kind));
}
BENCHMARK(BM_Estimator)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

void BM_IdentifyTree(benchmark::State& state) {
  identification::SyntheticMarkerTree tree;
  tree.root_motion[0] = {{0.9, 0.025, 0.01, 0.0}};
  for (int k = 0; k < 6; ++k) {
    identification::SyntheticLink link;
    link.parent = k == 0 ? -1 : (k - 1) / 2;
    link.rest_direction = Eigen::Vector3d(std::cos(k), -1.0, std::sin(k));
    link.length_m = 0.5;
    link.theta_u = {{1.0 + 0.1 * k, 0.03, 0.1, 0.0}};
    link.theta_w = {{1.0 + 0.1 * k, 0.03, 0.05, 1.0}};
    tree.links.push_back(link);
  }
  std::vector<MarkerLink> markers;
  const Trajectories t = tracking::SimulateTrackerError(
      identification::MakeMarkerTrajectories(tree, 30, 2, 10, &markers),
      tracking::TrackerErrorOptions{});
  identification::IdentifyOptions options;
  options.compare_estimators = state.range(0) != 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(identification::IdentifyMaterials(t, markers, options));
  state.SetLabel(options.compare_estimators ? "7 links, all estimators" : "7 links, default");
}
BENCHMARK(BM_IdentifyTree)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace simtree

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--tables") == 0) {
      simtree::NotesTable();
      simtree::ComparisonTable();
      return 0;
    }
    if (std::strcmp(argv[i], "--independent") == 0) {
      simtree::IndependentTable(i + 1 < argc ? std::atoi(argv[i + 1]) : 20);
      return 0;
    }
    if (std::strcmp(argv[i], "--score") == 0) {
      if (i + 2 >= argc) {
        std::fprintf(stderr, "usage: %s --score SCENE MATERIALS [READY_TREE]\n", argv[0]);
        return 2;
      }
      try {
        return simtree::Score(argv[i + 1], argv[i + 2], i + 3 < argc ? argv[i + 3] : "");
      } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
      }
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
