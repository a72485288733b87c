#include "simtree/dynamics/detail/node_deform.h"

#include <cmath>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace simtree::dynamics {
namespace {

// The branch's pose and modal coordinates in single precision.
struct NodePass {
  float o[3];
  float ru[3], rv[3], rw[3];
  float q_u, q_w, q_t;
};

// Small twists (|q_t| <= 1 rad, every realistic case): sin and cos by series, so there is no
// branch and no libm call. Error below 3e-8, under float resolution.
inline void TwistSinCos(float t, float* s, float* c) {
  const float t2 = t * t;
  *s = t * (1.f + t2 * (-1.f / 6 + t2 * (1.f / 120 + t2 * (-1.f / 5040 + t2 * (1.f / 362880)))));
  *c = 1.f + t2 * (-0.5f + t2 * (1.f / 24 +
                                 t2 * (-1.f / 720 + t2 * (1.f / 40320 + t2 * (-1.f / 3628800)))));
}

void DeformNodesSmallTwist(const NodePass& p, const float* __restrict__ hh,
                           const float* __restrict__ au, const float* __restrict__ aw,
                           const float* __restrict__ phi, const float* __restrict__ psi, int count,
                           float* __restrict__ out) {
  int i = 0;
#if defined(__SSE2__)
  // Four nodes at a time in SSE registers (x86-64 always has SSE2): the compiler does not
  // vectorise the interleaved xyz stores by itself.
  {
    const __m128 ox = _mm_set1_ps(p.o[0]), oy = _mm_set1_ps(p.o[1]), oz = _mm_set1_ps(p.o[2]);
    const __m128 ux = _mm_set1_ps(p.ru[0]), uy = _mm_set1_ps(p.ru[1]), uz = _mm_set1_ps(p.ru[2]);
    const __m128 vx = _mm_set1_ps(p.rv[0]), vy = _mm_set1_ps(p.rv[1]), vz = _mm_set1_ps(p.rv[2]);
    const __m128 wx = _mm_set1_ps(p.rw[0]), wy = _mm_set1_ps(p.rw[1]), wz = _mm_set1_ps(p.rw[2]);
    const __m128 qu = _mm_set1_ps(p.q_u), qw = _mm_set1_ps(p.q_w), qt = _mm_set1_ps(p.q_t);
    const auto k = [](float x) { return _mm_set1_ps(x); };
    for (; i + 4 <= count; i += 4) {
      const __m128 t = _mm_mul_ps(_mm_loadu_ps(psi + i), qt);
      const __m128 t2 = _mm_mul_ps(t, t);
      __m128 sn = _mm_add_ps(k(-1.f / 5040), _mm_mul_ps(t2, k(1.f / 362880)));
      sn = _mm_add_ps(k(1.f / 120), _mm_mul_ps(t2, sn));
      sn = _mm_add_ps(k(-1.f / 6), _mm_mul_ps(t2, sn));
      sn = _mm_mul_ps(t, _mm_add_ps(k(1.f), _mm_mul_ps(t2, sn)));
      __m128 cs = _mm_add_ps(k(1.f / 40320), _mm_mul_ps(t2, k(-1.f / 3628800)));
      cs = _mm_add_ps(k(-1.f / 720), _mm_mul_ps(t2, cs));
      cs = _mm_add_ps(k(1.f / 24), _mm_mul_ps(t2, cs));
      cs = _mm_add_ps(k(-0.5f), _mm_mul_ps(t2, cs));
      cs = _mm_add_ps(k(1.f), _mm_mul_ps(t2, cs));
      const __m128 a_u = _mm_loadu_ps(au + i), a_w = _mm_loadu_ps(aw + i);
      const __m128 f = _mm_loadu_ps(phi + i), h = _mm_loadu_ps(hh + i);
      const __m128 alpha =
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(cs, a_u), _mm_mul_ps(sn, a_w)), _mm_mul_ps(f, qu));
      const __m128 beta =
          _mm_add_ps(_mm_sub_ps(_mm_mul_ps(cs, a_w), _mm_mul_ps(sn, a_u)), _mm_mul_ps(f, qw));
      const auto axis = [&](__m128 o, __m128 v, __m128 u, __m128 w) {
        return _mm_add_ps(_mm_add_ps(o, _mm_mul_ps(h, v)),
                          _mm_add_ps(_mm_mul_ps(alpha, u), _mm_mul_ps(beta, w)));
      };
      const __m128 x = axis(ox, vx, ux, wx), y = axis(oy, vy, uy, wy), z = axis(oz, vz, uz, wz);
      // (x0..3, y0..3, z0..3) -> x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3
      const __m128 xy01 = _mm_unpacklo_ps(x, y);                            // x0 y0 x1 y1
      const __m128 xy23 = _mm_unpackhi_ps(x, y);                            // x2 y2 x3 y3
      const __m128 zx = _mm_shuffle_ps(z, xy01, _MM_SHUFFLE(2, 2, 0, 0));   // z0 z0 x1 x1
      const __m128 yz = _mm_shuffle_ps(xy01, z, _MM_SHUFFLE(1, 1, 3, 3));   // y1 y1 z1 z1
      const __m128 zx3 = _mm_shuffle_ps(z, xy23, _MM_SHUFFLE(2, 2, 2, 2));  // z2 z2 x3 x3
      const __m128 yz3 = _mm_shuffle_ps(xy23, z, _MM_SHUFFLE(3, 3, 3, 3));  // y3 y3 z3 z3
      _mm_storeu_ps(out + 3 * i + 0, _mm_shuffle_ps(xy01, zx, _MM_SHUFFLE(2, 0, 1, 0)));
      _mm_storeu_ps(out + 3 * i + 4, _mm_shuffle_ps(yz, xy23, _MM_SHUFFLE(1, 0, 2, 0)));
      _mm_storeu_ps(out + 3 * i + 8, _mm_shuffle_ps(zx3, yz3, _MM_SHUFFLE(2, 0, 2, 0)));
    }
  }
#endif
  for (; i < count; ++i) {
    float s = 0, c = 1;
    TwistSinCos(psi[i] * p.q_t, &s, &c);
    // The same operations in the same order as the SSE lanes: bit-identical results.
    const float alpha = (c * au[i] + s * aw[i]) + phi[i] * p.q_u;
    const float beta = (c * aw[i] - s * au[i]) + phi[i] * p.q_w;
    for (int a = 0; a < 3; ++a) {
      out[3 * i + a] = (p.o[a] + hh[i] * p.rv[a]) + (alpha * p.ru[a] + beta * p.rw[a]);
    }
  }
}

// Any twist: libm sin and cos per node.
void DeformNodesLargeTwist(const NodePass& p, const float* hh, const float* au, const float* aw,
                           const float* phi, const float* psi, int count, float* out) {
  for (int i = 0; i < count; ++i) {
    const float t = psi[i] * p.q_t;
    const float s = std::sin(t), c = std::cos(t);
    const float alpha = c * au[i] + s * aw[i] + phi[i] * p.q_u;
    const float beta = c * aw[i] - s * au[i] + phi[i] * p.q_w;
    for (int a = 0; a < 3; ++a) {
      out[3 * i + a] = p.o[a] + hh[i] * p.rv[a] + alpha * p.ru[a] + beta * p.rw[a];
    }
  }
}

}  // namespace

void DeformNodes(const NodeTables& node, const BranchLink& k, const BranchState& st,
                 Eigen::Vector3f* positions) {
  NodePass p;
  for (int a = 0; a < 3; ++a) {
    p.o[a] = static_cast<float>(st.origin[a]);
    p.ru[a] = static_cast<float>(st.frame(a, 0));
    p.rv[a] = static_cast<float>(st.frame(a, 1));
    p.rw[a] = static_cast<float>(st.frame(a, 2));
  }
  p.q_u = static_cast<float>(st.modal.q[kModeU]);
  p.q_w = static_cast<float>(st.modal.q[kModeW]);
  p.q_t = static_cast<float>(st.modal.q[kModeT]);
  const size_t f = k.first_node;
  float* out = positions[f].data();
  if (std::abs(st.modal.q[kModeT]) <= 1.0) {
    DeformNodesSmallTwist(p, &node.h[f], &node.a_u[f], &node.a_w[f], &node.phi[f], &node.psi[f],
                          k.nodes, out);
  } else {
    DeformNodesLargeTwist(p, &node.h[f], &node.a_u[f], &node.a_w[f], &node.phi[f], &node.psi[f],
                          k.nodes, out);
  }
}

}  // namespace simtree::dynamics
