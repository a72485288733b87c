#pragma once
// Natural modes of the FEM oracle: the lowest eigenpairs of K phi = omega^2 M phi.
//
// Large models use Spectra's shift-invert Lanczos for the generalized symmetric problem with a
// sparse LDL^T factorisation of K - sigma M (sigma slightly below zero, so the matrix is positive
// definite and the modes nearest zero, the lowest, converge first); models of a few hundred
// degrees of freedom are solved densely. Shapes are mass-normalised (phi^T M phi = 1, so the
// modal coordinates of a state are q = Phi^T M x), frequencies ascend, and each mode's damping
// ratio follows from the wood's Rayleigh coefficients: zeta = alpha / (2 omega) + beta omega / 2.

#include <Eigen/Core>

#include "simtree/synth/detail/fem_model.h"

namespace simtree::synth {

struct ModesOptions {
  // How many of the lowest modes (at most dof_count).
  int count = 60;
  // Also every mode below this frequency (Hz; 0: off): the count grows, up to `max_count`, until
  // the highest mode found lies above it.
  double cover_frequency_hz = 0.0;
  int max_count = 400;
  // Models with at most this many degrees of freedom are solved densely.
  int dense_limit = 600;
  // Lanczos convergence tolerance (relative, on the shift-inverted eigenvalues) and iteration cap.
  double tolerance = 1e-10;
  int max_iterations = 1000;
};

struct ModalBasis {
  Eigen::VectorXd omega;          // rad/s, ascending
  Eigen::VectorXd frequency_hz;   // omega / 2 pi
  Eigen::VectorXd damping_ratio;  // Rayleigh
  Eigen::MatrixXd shapes;         // dof_count x count, mass-normalised columns

  int count() const { return static_cast<int>(omega.size()); }
  // Modal coordinates of a displacement (or velocity) vector: Phi^T M x.
  Eigen::VectorXd Project(const Eigen::SparseMatrix<double>& mass, const Eigen::VectorXd& x) const;
};

// Throws InputError for options out of range, Error when the eigensolver does not converge.
ModalBasis ComputeModes(const FemModel& model, const ModesOptions& options = {});

}  // namespace simtree::synth
