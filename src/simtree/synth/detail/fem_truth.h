#pragma once
// The modal truth of a synthetic pull test (gt/modal.json, io/ground_truth.h's ModalTruth with
// source "fem"): which natural mode of the whole tree each measurement would see, with its
// frequency and damping ratio.
//
// Signals (what identification measures from marker trajectories, identification/deflection.h,
// restated here, not called: the oracle must not use code it scores):
//   - The root marker (parent -1): its displacement from rest (3D; the two principal directions
//     identification uses hold nearly all of it).
//   - A marker link, child marker c with parent marker p: the direction of the link p -> c, with
//     the swing of the parent link g -> p (the shortest rotation taking its rest direction to its
//     current one) taken out; for a link from the root marker, against the fixed world frame. The
//     signal is its angle from the rest direction, in both bending planes at once (a vector
//     normal to the link, radians).
//   - A branch: the direction of its chord (base -> tip), with the swing of its parent's tangent
//     at the attachment node (the shortest rotation of the tangent by that node's rotation: the
//     twist about the tangent does not count) taken out; the trunk against the world frame.
// Linearisation: every signal is linear in the displacements, s(t) = sum_i s_i q_i(t), with q_i
// the modal coordinates (mass-normalised modes) and s_i the signal of mode i's shape. After
// release from (x0, v0), mode i decays freely,
//   q_i(t) = e^(-zeta w t) (A cos w_d t + B sin w_d t),  A = q_i(0),  B = (q_i'(0) + zeta w A) /
//   w_d,
// so its amplitude in the signal is a_i = |s_i| sqrt(A^2 + B^2) (both planes together, velocity
// included). Modes of one frequency (within 1e-6: a round branch bends alike in two planes, and
// how an eigensolver splits such a pair is arbitrary) are one oscillation: their complex
// amplitude vectors sum(s_i (A_i - i B_i)) add before the norm, and they report their first mode.
// Dominance: the mode whose spectral peak over the record T after release would be highest: the
// magnitude of the Fourier integral over T of the whole signal at the mode's damped frequency,
//   strength_j = 2 | sum_i s_i F_i(w_j) |,  F_i(W) = integral_0^T q_i(t) e^(-i W t) dt,
// which is a_j (1 - e^(-zeta w T)) / (zeta w) for a mode far from the others. Modes closer than
// the record resolves (|f_i - f_j| T below about 1) add with their phases: two that cancel in a
// link's signal make no peak there, as in the record the identification sees, and a third, weaker
// by its own amplitude, can be the link's strongest.
// The result carries the dominant mode's frequency and damping and, in `peaks`, the two
// strongest modes. Its `modes` are all modes of the basis: pass enough (every mode below ~20 Hz,
// and at least 60) that the release state is represented.

#include <complex>

#include <Eigen/Core>

#include "simtree/core/tree.h"
#include "simtree/io/ground_truth.h"
#include "simtree/synth/detail/fem_model.h"
#include "simtree/synth/detail/fem_modes.h"
#include "simtree/synth/detail/fem_response.h"

namespace simtree::synth {

struct ModalTruthOptions {
  // The record after release the identification sees (s).
  double record_after_release_s = 10.0;
  // How many of the strongest modes to keep in each link's and branch's `peaks`.
  int peaks = 2;
};

// The Fourier integral over [0, record] of the free decay e^(-zeta omega t) (cos_part cos w_d t +
// sin_part sin w_d t), w_d = omega sqrt(1 - zeta^2), at angular frequency `at` (closed form).
std::complex<double> DecayFourierIntegral(double omega, double zeta, double cos_part,
                                          double sin_part, double at, double record);

// `tree` is the model's tree with its markers (its branches must match the model's). Links follow
// the markers in id order, the root marker's displacement first; branches in id order (a branch
// whose chord has zero length is left out). Throws InputError for a tree that does not match the
// model, markers that coincide with their parent marker, a release state of the wrong size, or
// options out of range.
ModalTruth ComputeModalTruth(const FemModel& model, const ModalBasis& modes, const Tree& tree,
                             const FemState& release_state, const ModalTruthOptions& options = {});

}  // namespace simtree::synth
