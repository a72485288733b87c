#include "simtree/synth/detail/fem_modes.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "simtree/core/error.h"
#include "simtree/core/progress.h"

namespace simtree::synth {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Models above this many degrees of freedom show progress.
constexpr int kProgressDofs = 20000;

// y = (K - sigma M)^-1 x through a sparse LDL^T factorisation: what Spectra's shift-invert mode
// asks of its operator. (Spectra's own SymShiftInvert uses a sparse LU; K - sigma M is symmetric
// positive definite for sigma < 0, so LDL^T with a fill-reducing ordering is cheaper.)
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(const SparseMatrix& k, const SparseMatrix& m) : k_(k), m_(m) {}
  Eigen::Index rows() const { return k_.rows(); }
  Eigen::Index cols() const { return k_.cols(); }
  void set_shift(double sigma) {
    solver_.compute(k_ - sigma * m_);
    if (solver_.info() != Eigen::Success) {
      throw Error(
          "fem modes: the stiffness matrix could not be factorised (is the tree clamped "
          "and connected?)");
    }
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = solver_.solve(x);
  }

 private:
  const SparseMatrix& k_;
  const SparseMatrix& m_;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> solver_;
};

// Eigenvalues (omega^2, ascending) and mass-normalised vectors of the `count` lowest modes.
struct EigenPairs {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};

EigenPairs DenseLowest(const FemModel& model, int count) {
  const Eigen::MatrixXd k(model.stiffness());
  const Eigen::MatrixXd m(model.mass());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, m);
  if (solver.info() != Eigen::Success) throw Error("fem modes: the dense eigensolver failed");
  return {solver.eigenvalues().head(count), solver.eigenvectors().leftCols(count)};
}

EigenPairs SparseLowest(const FemModel& model, int count, const ModesOptions& options) {
  const int n = model.dof_count();
  ShiftInvertOperator op(model.stiffness(), model.mass());
  Spectra::SparseSymMatProd<double> mass_op(model.mass());
  const int ncv = std::min(n, std::max(2 * count + 1, count + 20));
  // Just below zero: K - sigma M stays positive definite and the lowest modes lie nearest.
  const double sigma = -1.0;
  Spectra::SymGEigsShiftSolver<ShiftInvertOperator, Spectra::SparseSymMatProd<double>,
                               Spectra::GEigsMode::ShiftInvert>
      solver(op, mass_op, count, ncv, sigma);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
                 Spectra::SortRule::SmallestAlge);
  if (solver.info() != Spectra::CompInfo::Successful) {
    throw Error(
        fmt::format("fem modes: the eigensolver did not converge on {} modes of {} degrees "
                    "of freedom in {} iterations",
                    count, n, options.max_iterations));
  }
  return {solver.eigenvalues(), solver.eigenvectors()};
}

}  // namespace

Eigen::VectorXd ModalBasis::Project(const Eigen::SparseMatrix<double>& mass,
                                    const Eigen::VectorXd& x) const {
  return shapes.transpose() * (mass * x);
}

ModalBasis ComputeModes(const FemModel& model, const ModesOptions& options) {
  if (options.count < 1 || options.max_count < options.count) {
    throw InputError("modes options", "count",
                     fmt::format("expected 1 <= count <= max_count, got count {} and max_count {}",
                                 options.count, options.max_count));
  }
  if (!std::isfinite(options.cover_frequency_hz) || options.cover_frequency_hz < 0 ||
      !(options.tolerance > 0) || options.max_iterations < 1) {
    throw InputError("modes options", "",
                     "expected cover_frequency_hz >= 0, tolerance > 0 and max_iterations >= 1");
  }
  const int n = model.dof_count();
  const bool dense = n <= options.dense_limit;
  // Spectra needs count < n; the dense solver gives all n.
  const int limit = dense ? n : n - 1;
  const double cover_omega_sq = std::pow(kTwoPi * options.cover_frequency_hz, 2);
  // Tens of thousands of degrees of freedom take seconds: say so (Spectra reports nothing while
  // it iterates, so this is one line per solve).
  std::unique_ptr<Progress> progress;
  if (n > kProgressDofs) progress = std::make_unique<Progress>("fem modes", 0, "modes");
  EigenPairs pairs;
  for (int count = std::min(options.count, limit);;) {
    pairs = dense ? DenseLowest(model, count) : SparseLowest(model, count, options);
    if (progress) progress->Advance(count);
    const bool covered = pairs.values[pairs.values.size() - 1] >= cover_omega_sq;
    const int cap = std::min(options.max_count, limit);
    if (covered || count >= cap) break;
    count = std::min(count + std::max(1, count / 2), cap);
  }
  // The order Spectra returns is ascending already; sort anyway so the dense and sparse paths
  // agree whatever the solvers do.
  std::vector<int> order(pairs.values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return pairs.values[a] < pairs.values[b]; });
  const int count = static_cast<int>(order.size());
  ModalBasis basis;
  basis.omega.resize(count);
  basis.frequency_hz.resize(count);
  basis.damping_ratio.resize(count);
  basis.shapes.resize(n, count);
  for (int i = 0; i < count; ++i) {
    const double lambda = pairs.values[order[i]];
    if (!(lambda > 0)) {
      throw Error(fmt::format("fem modes: eigenvalue {} is not positive ({}): the tree is not held",
                              i, lambda));
    }
    Eigen::VectorXd phi = pairs.vectors.col(order[i]);
    phi /= std::sqrt(phi.dot(model.mass() * phi));
    // A sign convention so that results do not flip between runs and solvers: the largest
    // component is positive.
    Eigen::Index largest = 0;
    phi.cwiseAbs().maxCoeff(&largest);
    if (phi[largest] < 0) phi = -phi;
    basis.shapes.col(i) = phi;
    basis.omega[i] = std::sqrt(lambda);
    basis.frequency_hz[i] = basis.omega[i] / kTwoPi;
    basis.damping_ratio[i] = model.wood().DampingRatioAt(basis.frequency_hz[i]);
  }
  return basis;
}

}  // namespace simtree::synth
