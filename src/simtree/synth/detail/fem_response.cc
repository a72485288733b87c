#include "simtree/synth/detail/fem_response.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include "simtree/core/error.h"
#include "simtree/core/progress.h"

namespace simtree::synth {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;

// Two times closer than this are the same instant (s).
constexpr double kSameTime = 1e-9;
// Show progress only for runs that take a while (degrees of freedom x steps).
constexpr double kProgressWork = 5e7;

void Factorise(Ldlt& solver, const SparseMatrix& matrix, const char* what) {
  solver.compute(matrix);
  if (solver.info() != Eigen::Success) {
    throw Error(fmt::format("fem: the {} could not be factorised (is the tree clamped?)", what));
  }
}

void CheckVector(const Eigen::VectorXd& v, int size, const char* source, const char* what) {
  if (v.size() != size) {
    throw InputError(source, what, fmt::format("expected {} values, got {}", size, v.size()));
  }
  if (!v.allFinite()) throw InputError(source, what, "expected finite values, got NaN or infinity");
}

// The Newmark average-acceleration coefficients for step dt.
struct NewmarkCoefficients {
  double a0, a1, a2;  // 4/dt^2, 2/dt, 4/dt
  explicit NewmarkCoefficients(double dt) : a0(4.0 / (dt * dt)), a1(2.0 / dt), a2(4.0 / dt) {}
};

// What the direct and the modal integrators have in their own coordinates; the stepping, the
// time plan and the sampling are shared (Drive below).
class NewmarkSystem {
 public:
  virtual ~NewmarkSystem() = default;
  virtual int size() const = 0;
  virtual void SetTimeStep(double dt) = 0;
  // a from equilibrium, M a = s p - C v - K x.
  virtual Eigen::VectorXd Acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                       double s) = 0;
  // x at the end of the step: K_eff x' = s' p + M (a0 x + a2 v + a) + C (a1 x + v).
  virtual Eigen::VectorXd Advance(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& a, double s_next) = 0;
  virtual FemState Sample(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                          const Eigen::VectorXd& a, double s) const = 0;
  // Hands sample `index` to `on_sample`, at once or (modal) with a batch; Flush() hands out what
  // is held back. Samples always arrive in order.
  virtual void Emit(int index, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                    const Eigen::VectorXd& a, double s, const FemSampleCallback& on_sample) {
    on_sample(index, t, Sample(t, x, v, a, s));
  }
  virtual void Flush(const FemSampleCallback&) {}
};

class DirectSystem final : public NewmarkSystem {
 public:
  DirectSystem(const FemModel& model, const FemLoad& load)
      : model_(model), pattern_(load.pattern) {}
  int size() const override { return model_.dof_count(); }

  void SetTimeStep(double dt) override {
    if (dt_ && std::abs(*dt_ - dt) <= 1e-12 * dt) return;
    dt_ = dt;
    coefficients_.emplace(dt);
    const SparseMatrix effective = model_.stiffness() + coefficients_->a1 * model_.damping() +
                                   coefficients_->a0 * model_.mass();
    Factorise(effective_, effective, "effective stiffness");
  }

  Eigen::VectorXd Acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                               double s) override {
    if (!mass_factorised_) {
      Factorise(mass_solver_, model_.mass(), "mass matrix");
      mass_factorised_ = true;
    }
    const WoodProperties& w = model_.wood();
    Eigen::VectorXd rhs = -(model_.stiffness() * (x + w.rayleigh_beta * v));
    if (pattern_.size()) rhs += s * pattern_;
    Eigen::VectorXd a = mass_solver_.solve(rhs);
    a -= w.rayleigh_alpha * v;
    return a;
  }

  Eigen::VectorXd Advance(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                          const Eigen::VectorXd& a, double s_next) override {
    // C = alpha M + beta K, so M and K products suffice.
    const NewmarkCoefficients& c = *coefficients_;
    const WoodProperties& w = model_.wood();
    const Eigen::VectorXd by_mass =
        (c.a0 + w.rayleigh_alpha * c.a1) * x + (c.a2 + w.rayleigh_alpha) * v + a;
    Eigen::VectorXd rhs = model_.mass() * by_mass;
    if (w.rayleigh_beta != 0) rhs += model_.stiffness() * (w.rayleigh_beta * (c.a1 * x + v));
    if (pattern_.size()) rhs += s_next * pattern_;
    return effective_.solve(rhs);
  }

  FemState Sample(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                  const Eigen::VectorXd& a, double) const override {
    return {t, x, v, a};
  }

 private:
  const FemModel& model_;
  const Eigen::VectorXd& pattern_;
  std::optional<double> dt_;
  std::optional<NewmarkCoefficients> coefficients_;
  Ldlt effective_;
  Ldlt mass_solver_;
  bool mass_factorised_ = false;
};

class ModalSystem final : public NewmarkSystem {
 public:
  ModalSystem(const FemModel& model, const ModalBasis& modes, const FemLoad& load,
              bool sample_rates)
      : modes_(modes), sample_rates_(sample_rates) {
    omega_sq_ = modes.omega.array().square();
    damping_ = 2.0 * modes.damping_ratio.array() * modes.omega.array();
    if (load.pattern.size()) {
      generalized_ = modes.shapes.transpose() * load.pattern;
      // The static response of the modes left out: K^-1 p minus what the basis gives.
      residual_ = SolveStatic(model, load.pattern) -
                  modes.shapes * (generalized_.array() / omega_sq_).matrix();
    } else {
      generalized_ = Eigen::VectorXd::Zero(modes.count());
    }
  }
  int size() const override { return modes_.count(); }

  void SetTimeStep(double dt) override {
    coefficients_.emplace(dt);
    effective_ = omega_sq_ + coefficients_->a1 * damping_ + coefficients_->a0;
  }

  Eigen::VectorXd Acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               double s) override {
    return (s * generalized_.array() - damping_ * qd.array() - omega_sq_ * q.array()).matrix();
  }

  Eigen::VectorXd Advance(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                          const Eigen::VectorXd& qdd, double s_next) override {
    const NewmarkCoefficients& c = *coefficients_;
    const Eigen::ArrayXd rhs = s_next * generalized_.array() + c.a0 * q.array() +
                               c.a2 * qd.array() + qdd.array() +
                               damping_ * (c.a1 * q.array() + qd.array());
    return (rhs / effective_).matrix();
  }

  FemState Sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                  const Eigen::VectorXd& qdd, double s) const override {
    FemState state;
    state.time_s = t;
    state.x = modes_.shapes * q;
    if (residual_.size() && s != 0) state.x += s * residual_;
    state.v = modes_.shapes * qd;
    state.a = modes_.shapes * qdd;
    return state;
  }

  // Physical states are the shapes times modal coordinates: one product for a batch of samples
  // reads the (large) shape matrix once instead of once per sample.
  void Emit(int index, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
            const Eigen::VectorXd& qdd, double s, const FemSampleCallback& on_sample) override {
    if (batch_.cols() == 0) batch_.resize(modes_.count(), 3 * kBatch);
    const bool rates = sample_rates_ || index == rates_index_;
    Pending p{index, t, s, used_columns_, rates};
    batch_.col(used_columns_++) = q;
    if (rates) {
      batch_.col(used_columns_++) = qd;
      batch_.col(used_columns_++) = qdd;
    }
    pending_.push_back(p);
    if (static_cast<int>(pending_.size()) == kBatch) Flush(on_sample);
  }

  void Flush(const FemSampleCallback& on_sample) override {
    if (pending_.empty()) return;
    const Eigen::MatrixXd physical = modes_.shapes * batch_.leftCols(used_columns_);
    for (const Pending& p : pending_) {
      FemState state;
      state.time_s = p.time_s;
      state.x = physical.col(p.column);
      if (residual_.size() && p.scale != 0) state.x += p.scale * residual_;
      if (p.rates) {
        state.v = physical.col(p.column + 1);
        state.a = physical.col(p.column + 2);
      }
      on_sample(p.index, state.time_s, state);
    }
    pending_.clear();
    used_columns_ = 0;
  }

  // This sample gets v and a even when sample_rates is off (the pull's release state).
  void SetRatesIndex(int index) { rates_index_ = index; }

 private:
  const ModalBasis& modes_;
  bool sample_rates_;
  int rates_index_ = -1;
  Eigen::ArrayXd omega_sq_, damping_, effective_;
  Eigen::VectorXd generalized_;  // Phi^T p
  Eigen::VectorXd residual_;     // static response of the modes left out, per unit scale
  std::optional<NewmarkCoefficients> coefficients_;
  // Samples waiting for their batch product.
  static constexpr int kBatch = 32;
  struct Pending {
    int index;
    double time_s;
    double scale;
    int column;  // of q in batch_ (qd, qdd follow when `rates`)
    bool rates;
  };
  std::vector<Pending> pending_;
  Eigen::MatrixXd batch_;  // modal coordinates of the pending samples, a column each
  int used_columns_ = 0;
};

void CheckSampleTimes(std::span<const double> times, double start) {
  for (size_t i = 0; i < times.size(); ++i) {
    const std::string at = fmt::format("sample_times[{}]", i);
    if (!std::isfinite(times[i])) throw InputError("newmark", at, "expected a finite time");
    if (times[i] < start - kSameTime) {
      throw InputError(
          "newmark", at,
          fmt::format("expected a time not before the start {} s, got {}", start, times[i]));
    }
    if (i > 0 && times[i] < times[i - 1]) {
      throw InputError("newmark", at, "expected ascending sample times");
    }
  }
}

// The shared Newmark loop: stretches between the load's jumps, equal steps within each, samples
// interpolated with the step's constant average acceleration.
NewmarkResult Drive(NewmarkSystem& system, double t0, Eigen::VectorXd x, Eigen::VectorXd v,
                    const FemLoad& load, std::span<const double> samples,
                    const NewmarkOptions& options, const FemSampleCallback& on_sample,
                    const char* stage) {
  if (!std::isfinite(options.max_time_step_s) || options.max_time_step_s <= 0) {
    throw InputError("newmark", "max_time_step_s",
                     fmt::format("expected a positive time step, got {}", options.max_time_step_s));
  }
  CheckSampleTimes(samples, t0);
  NewmarkResult result;
  const double t_end = samples.empty() ? t0 : std::max(t0, samples.back());
  std::vector<double> stops;
  for (double jump : load.jumps_s) {
    if (jump > t0 + kSameTime && jump < t_end - kSameTime) stops.push_back(jump);
  }
  std::sort(stops.begin(), stops.end());
  stops.push_back(t_end);
  const auto is_jump = [&](double t) {
    return std::any_of(load.jumps_s.begin(), load.jumps_s.end(),
                       [&](double j) { return std::abs(j - t) <= kSameTime; });
  };

  int64_t total_steps = 0;
  {
    double ta = t0;
    for (double tb : stops) {
      total_steps += std::max<int64_t>(
          tb - ta > kSameTime ? 1 : 0,
          static_cast<int64_t>(std::ceil((tb - ta) / options.max_time_step_s - 1e-9)));
      ta = tb;
    }
  }
  std::unique_ptr<Progress> progress;
  if (static_cast<double>(system.size()) * total_steps > kProgressWork) {
    progress = std::make_unique<Progress>(stage, total_steps, "steps");
  }

  size_t next = 0;
  Eigen::VectorXd a = system.Acceleration(x, v, load.ScaleAt(t0));
  while (next < samples.size() && samples[next] <= t0 + kSameTime) {
    system.Emit(static_cast<int>(next), samples[next], x, v, a, load.ScaleAt(t0), on_sample);
    ++next;
  }
  double t = t0;
  for (double tb : stops) {
    const double ta = t;
    if (tb - ta <= kSameTime) continue;
    const int64_t steps = std::max<int64_t>(
        1, static_cast<int64_t>(std::ceil((tb - ta) / options.max_time_step_s - 1e-9)));
    const double dt = (tb - ta) / static_cast<double>(steps);
    system.SetTimeStep(dt);
    result.time_step_s = dt;
    const NewmarkCoefficients c(dt);
    // After a jump the acceleration changes at once: re-solve it with the load after the jump.
    if (ta > t0) a = system.Acceleration(x, v, load.ScaleAt(ta));
    const bool ends_on_jump = is_jump(tb);
    for (int64_t k = 1; k <= steps; ++k) {
      const double t_next = k == steps ? tb : ta + static_cast<double>(k) * dt;
      // The last step before a jump feels the load just before it (its left limit).
      const double s_next =
          (k == steps && ends_on_jump)
              ? load.ScaleAt(std::nextafter(tb, -std::numeric_limits<double>::infinity()))
              : load.ScaleAt(t_next);
      Eigen::VectorXd x_next = system.Advance(x, v, a, s_next);
      Eigen::VectorXd a_next = c.a0 * (x_next - x) - c.a2 * v - a;
      Eigen::VectorXd v_next = v + 0.5 * dt * (a + a_next);
      while (next < samples.size() && samples[next] <= t_next + kSameTime) {
        const double ts = samples[next];
        if (std::abs(ts - t_next) <= kSameTime) {
          system.Emit(static_cast<int>(next), ts, x_next, v_next, a_next, s_next, on_sample);
        } else {
          const double tau = ts - t;
          const Eigen::VectorXd mean_a = 0.5 * (a + a_next);
          system.Emit(static_cast<int>(next), ts, x + tau * v + 0.5 * tau * tau * mean_a,
                      v + tau * mean_a, a + (tau / dt) * (a_next - a), load.ScaleAt(ts), on_sample);
        }
        ++next;
      }
      x = std::move(x_next);
      v = std::move(v_next);
      a = std::move(a_next);
      t = t_next;
      ++result.steps;
      if (progress) progress->Advance();
    }
  }
  system.Flush(on_sample);
  result.final_state = system.Sample(t, x, v, a, load.ScaleAt(t));
  return result;
}

void CheckStart(const FemModel& model, const FemState& start, const FemLoad& load) {
  if (!std::isfinite(start.time_s)) throw InputError("newmark", "start.time_s", "expected finite");
  const int n = model.dof_count();
  if (start.x.size()) CheckVector(start.x, n, "newmark", "start.x");
  if (start.v.size()) CheckVector(start.v, n, "newmark", "start.v");
  if (load.pattern.size()) CheckVector(load.pattern, n, "newmark", "load.pattern");
}

Eigen::VectorXd OrZero(const Eigen::VectorXd& v, int n) {
  return v.size() ? v : Eigen::VectorXd::Zero(n);
}

void CheckModes(const FemModel& model, const ModalBasis& modes) {
  if (modes.count() == 0 || modes.shapes.rows() != model.dof_count()) {
    throw InputError("newmark", "modes",
                     fmt::format("expected modes of this model ({} degrees of freedom), got {} "
                                 "modes of {}",
                                 model.dof_count(), modes.count(), modes.shapes.rows()));
  }
}

}  // namespace

FemState RestState(const FemModel& model, double time_s) {
  const int n = model.dof_count();
  return {time_s, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
}

Eigen::VectorXd SolveStatic(const FemModel& model, const Eigen::VectorXd& force) {
  CheckVector(force, model.dof_count(), "static solve", "force");
  Ldlt solver;
  Factorise(solver, model.stiffness(), "stiffness matrix");
  return solver.solve(force);
}

NewmarkResult IntegrateNewmark(const FemModel& model, const FemState& start, const FemLoad& load,
                               std::span<const double> sample_times, const NewmarkOptions& options,
                               const FemSampleCallback& on_sample) {
  CheckStart(model, start, load);
  DirectSystem system(model, load);
  const int n = model.dof_count();
  return Drive(system, start.time_s, OrZero(start.x, n), OrZero(start.v, n), load, sample_times,
               options, on_sample, "fem newmark (direct)");
}

namespace {

// The modal integration, with one sample (`rates_index`, -1: none) that always gets v and a.
NewmarkResult IntegrateModal(const FemModel& model, const ModalBasis& modes, const FemState& start,
                             const FemLoad& load, std::span<const double> sample_times,
                             const NewmarkOptions& options, const FemSampleCallback& on_sample,
                             int rates_index) {
  CheckStart(model, start, load);
  CheckModes(model, modes);
  ModalSystem system(model, modes, load, options.sample_rates);
  system.SetRatesIndex(rates_index);
  const int n = model.dof_count();
  return Drive(system, start.time_s, modes.Project(model.mass(), OrZero(start.x, n)),
               modes.Project(model.mass(), OrZero(start.v, n)), load, sample_times, options,
               on_sample, "fem newmark (modal)");
}

}  // namespace

NewmarkResult IntegrateNewmark(const FemModel& model, const ModalBasis& modes,
                               const FemState& start, const FemLoad& load,
                               std::span<const double> sample_times, const NewmarkOptions& options,
                               const FemSampleCallback& on_sample) {
  return IntegrateModal(model, modes, start, load, sample_times, options, on_sample, -1);
}

FemLoad PullFemLoad(const FemModel& model, const PullLoad& pull) {
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(pull.force_n) || pull.force_n < 0) {
    throw InputError("pull load", "force_n",
                     fmt::format("expected a force >= 0 N, got {}", pull.force_n));
  }
  if (!finite(pull.ramp_start_s) || !finite(pull.hold_start_s) || !finite(pull.release_s) ||
      !(0 <= pull.ramp_start_s && pull.ramp_start_s <= pull.hold_start_s &&
        pull.hold_start_s <= pull.release_s)) {
    throw InputError("pull load", "release_s",
                     "expected finite times 0 <= ramp_start_s <= hold_start_s <= release_s");
  }
  const Eigen::Vector3d along = pull.anchor - pull.attach_point;
  if (!along.allFinite() || along.norm() < 1e-9) {
    throw InputError("pull load", "anchor", "expected an anchor away from the attach point");
  }
  FemLoad load;
  load.pattern = model.PointLoad(pull.branch, pull.arc_length, along.normalized());
  load.scale = [pull](double t) { return pull.ForceAt(t); };
  load.jumps_s = {pull.release_s};
  return load;
}

namespace {

// Runs `integrate` over the caller's samples plus the release instant, and keeps the state there.
template <typename Integrate>
PullResult RunPull(const PullLoad& pull, std::span<const double> sample_times,
                   const FemSampleCallback& on_sample, Integrate&& integrate) {
  CheckSampleTimes(sample_times, 0.0);
  std::vector<double> times(sample_times.begin(), sample_times.end());
  const auto at = std::lower_bound(times.begin(), times.end(), pull.release_s);
  const int release_index = static_cast<int>(at - times.begin());
  times.insert(at, pull.release_s);
  PullResult result;
  result.run = integrate(std::span<const double>(times), release_index,
                         [&](int i, double t, const FemState& s) {
                           if (i == release_index) {
                             result.release_state = s;
                             return;
                           }
                           on_sample(i < release_index ? i : i - 1, t, s);
                         });
  return result;
}

}  // namespace

PullResult IntegratePull(const FemModel& model, const PullLoad& pull,
                         std::span<const double> sample_times, const NewmarkOptions& options,
                         const FemSampleCallback& on_sample) {
  const FemLoad load = PullFemLoad(model, pull);
  return RunPull(pull, sample_times, on_sample, [&](std::span<const double> t, int, auto&& cb) {
    return IntegrateNewmark(model, RestState(model), load, t, options, cb);
  });
}

PullResult IntegratePull(const FemModel& model, const ModalBasis& modes, const PullLoad& pull,
                         std::span<const double> sample_times, const NewmarkOptions& options,
                         const FemSampleCallback& on_sample) {
  const FemLoad load = PullFemLoad(model, pull);
  // The release state feeds the modal truth, which needs velocities, whatever the options say.
  return RunPull(
      pull, sample_times, on_sample, [&](std::span<const double> t, int release_index, auto&& cb) {
        return IntegrateModal(model, modes, RestState(model), load, t, options, cb, release_index);
      });
}

NewmarkResult IntegrateFree(const FemModel& model, const ModalBasis& modes, const FemState& start,
                            std::span<const double> sample_times, const NewmarkOptions& options,
                            const FemSampleCallback& on_sample) {
  return IntegrateNewmark(model, modes, start, FemLoad{}, sample_times, options, on_sample);
}

FemState RandomVibrationState(const FemModel& model, const ModalBasis& modes,
                              const VibrationOptions& options) {
  CheckModes(model, modes);
  if (!std::isfinite(options.amplitude_m) || options.amplitude_m < 0 || options.mode_count < 1) {
    throw InputError("vibration", "", "expected amplitude_m >= 0 and mode_count >= 1");
  }
  const int count = std::min(options.mode_count, modes.count());
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd q(count), qd(count);
  for (int i = 0; i < count; ++i) {
    const double amplitude = (0.5 + 0.5 * unit(rng)) * modes.omega[0] / modes.omega[i];
    const double phase = kTwoPi * unit(rng);
    q[i] = amplitude * std::cos(phase);
    qd[i] = -modes.omega[i] * amplitude * std::sin(phase);
  }
  // Free vibration: each mode's acceleration is -omega^2 q - 2 zeta omega qd.
  const Eigen::ArrayXd omega = modes.omega.head(count).array();
  const Eigen::VectorXd qdd = (-omega.square() * q.array() -
                               2.0 * modes.damping_ratio.head(count).array() * omega * qd.array())
                                  .matrix();
  FemState state = RestState(model);
  state.x = modes.shapes.leftCols(count) * q;
  state.v = modes.shapes.leftCols(count) * qd;
  state.a = modes.shapes.leftCols(count) * qdd;
  double largest = 0.0;
  for (int node = 1; node < model.node_count(); ++node) {
    largest = std::max(largest, state.x.segment<3>(model.node_dof(node)).norm());
  }
  const double scale = largest > 0 ? options.amplitude_m / largest : 0.0;
  state.x *= scale;
  state.v *= scale;
  state.a *= scale;
  return state;
}

double MechanicalEnergy(const FemModel& model, const FemState& state) {
  return 0.5 * state.v.dot(model.mass() * state.v) + 0.5 * state.x.dot(model.stiffness() * state.x);
}

}  // namespace simtree::synth
