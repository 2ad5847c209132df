// Internal: two doubles computed together — the pair kernel's lanes (pair_kernel.h).
//
// SSE2 is part of x86-64, so no runtime dispatch is needed; elsewhere a plain pair of doubles
// gives the same answers. Every operation is one IEEE operation per lane, rounded as the
// scalar one is: a kernel written with lanes computes bit for bit what the same expression
// computes on scalars, which is how exact mode keeps its answers.
#pragma once

#if defined(__SSE2__) || defined(_M_X64)
#define ADB_LANES_SSE2 1
#include <emmintrin.h>
#else
#define ADB_LANES_SSE2 0
#include <algorithm>
#include <cmath>
#endif

namespace adb::detail {

#if ADB_LANES_SSE2

struct Lanes {
  __m128d v;

  static Lanes of(double lane0, double lane1) { return {_mm_set_pd(lane1, lane0)}; }
  static Lanes all(double x) { return {_mm_set1_pd(x)}; }
  /// Lane k of this value in both lanes.
  Lanes broadcast(int k) const {
    return {k == 0 ? _mm_unpacklo_pd(v, v) : _mm_unpackhi_pd(v, v)};
  }
  double lane(int k) const {
    return k == 0 ? _mm_cvtsd_f64(v) : _mm_cvtsd_f64(_mm_unpackhi_pd(v, v));
  }
};

inline Lanes operator+(Lanes x, Lanes y) { return {_mm_add_pd(x.v, y.v)}; }
inline Lanes operator-(Lanes x, Lanes y) { return {_mm_sub_pd(x.v, y.v)}; }
inline Lanes operator*(Lanes x, Lanes y) { return {_mm_mul_pd(x.v, y.v)}; }
inline Lanes abs(Lanes x) { return {_mm_andnot_pd(_mm_set1_pd(-0.0), x.v)}; }
// For finite values (all the kernel sees) these are std::max / std::min, up to the sign of
// a zero.
inline Lanes max(Lanes x, Lanes y) { return {_mm_max_pd(x.v, y.v)}; }
inline Lanes min(Lanes x, Lanes y) { return {_mm_min_pd(x.v, y.v)}; }

/// A per-lane truth value (all bits set or clear).
struct LaneMask {
  __m128d v;
  /// Bit k set where lane k is true.
  int bits() const { return _mm_movemask_pd(v); }
};
inline LaneMask operator>(Lanes x, Lanes y) { return {_mm_cmpgt_pd(x.v, y.v)}; }
inline LaneMask operator>=(Lanes x, Lanes y) { return {_mm_cmpge_pd(x.v, y.v)}; }
inline LaneMask operator|(LaneMask x, LaneMask y) { return {_mm_or_pd(x.v, y.v)}; }
/// Lanes of `yes` where the mask is true, of `no` elsewhere.
inline Lanes select(LaneMask m, Lanes yes, Lanes no) {
  return {_mm_or_pd(_mm_and_pd(m.v, yes.v), _mm_andnot_pd(m.v, no.v))};
}

/// Each lane rounded towards zero; |lanes| < 2^31.
inline Lanes truncated(Lanes x) { return {_mm_cvtepi32_pd(_mm_cvttpd_epi32(x.v))}; }
/// Each lane as an int (integral lanes, |lanes| < 2^31).
inline void toInts(Lanes x, int out[2]) {
  const __m128i i = _mm_cvttpd_epi32(x.v);
  out[0] = _mm_cvtsi128_si32(i);
  out[1] = _mm_cvtsi128_si32(_mm_shuffle_epi32(i, 1));
}

/// Four consecutive floats of two records as four lanes: out[k] = (p0[k], p1[k]). Float to
/// double is exact, so this is what converting each float gives.
inline void loadFloatPairs(const float* p0, const float* p1, Lanes out[4]) {
  const __m128 v0 = _mm_loadu_ps(p0);
  const __m128 v1 = _mm_loadu_ps(p1);
  const __m128 low = _mm_unpacklo_ps(v0, v1);   // p0[0] p1[0] p0[1] p1[1]
  const __m128 high = _mm_unpackhi_ps(v0, v1);  // p0[2] p1[2] p0[3] p1[3]
  out[0] = {_mm_cvtps_pd(low)};
  out[1] = {_mm_cvtps_pd(_mm_movehl_ps(low, low))};
  out[2] = {_mm_cvtps_pd(high)};
  out[3] = {_mm_cvtps_pd(_mm_movehl_ps(high, high))};
}

#else

struct Lanes {
  double v[2];

  static Lanes of(double lane0, double lane1) { return {{lane0, lane1}}; }
  static Lanes all(double x) { return {{x, x}}; }
  Lanes broadcast(int k) const { return {{v[k], v[k]}}; }
  double lane(int k) const { return v[k]; }
};

inline Lanes operator+(Lanes x, Lanes y) { return {{x.v[0] + y.v[0], x.v[1] + y.v[1]}}; }
inline Lanes operator-(Lanes x, Lanes y) { return {{x.v[0] - y.v[0], x.v[1] - y.v[1]}}; }
inline Lanes operator*(Lanes x, Lanes y) { return {{x.v[0] * y.v[0], x.v[1] * y.v[1]}}; }
inline Lanes abs(Lanes x) { return {{std::abs(x.v[0]), std::abs(x.v[1])}}; }
inline Lanes max(Lanes x, Lanes y) {
  return {{std::max(x.v[0], y.v[0]), std::max(x.v[1], y.v[1])}};
}
inline Lanes min(Lanes x, Lanes y) {
  return {{std::min(x.v[0], y.v[0]), std::min(x.v[1], y.v[1])}};
}

struct LaneMask {
  bool v[2];
  int bits() const { return (v[0] ? 1 : 0) | (v[1] ? 2 : 0); }
};
inline LaneMask operator>(Lanes x, Lanes y) { return {{x.v[0] > y.v[0], x.v[1] > y.v[1]}}; }
inline LaneMask operator>=(Lanes x, Lanes y) { return {{x.v[0] >= y.v[0], x.v[1] >= y.v[1]}}; }
inline LaneMask operator|(LaneMask x, LaneMask y) {
  return {{x.v[0] || y.v[0], x.v[1] || y.v[1]}};
}
inline Lanes select(LaneMask m, Lanes yes, Lanes no) {
  return {{m.v[0] ? yes.v[0] : no.v[0], m.v[1] ? yes.v[1] : no.v[1]}};
}

inline void loadFloatPairs(const float* p0, const float* p1, Lanes out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = Lanes::of(p0[k], p1[k]);
}
inline Lanes truncated(Lanes x) { return {{std::trunc(x.v[0]), std::trunc(x.v[1])}}; }
inline void toInts(Lanes x, int out[2]) {
  out[0] = static_cast<int>(x.v[0]);
  out[1] = static_cast<int>(x.v[1]);
}

#endif

}  // namespace adb::detail
