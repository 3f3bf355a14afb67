// Particles in packs (docs/performance.md, "SIMD across particles"): Pack holds one double per
// particle of a block, as many as the build's vector registers take (ANODE_SIMD: 8 with AVX-512,
// 4 with AVX2, 2 with SSE2), and Eigen's fixed-size matrices take it as their scalar, so one
// equation written for a scalar S serves one particle (S = double) or a pack of them (S = Pack).
// Each lane does the same operations in the same order as the scalar code, so a particle's
// result does not depend on the pack it is in or on the vector width.
#pragma once

#include <experimental/simd>

#include "Core/Math/Types.h"

namespace anode {

namespace stdx = std::experimental;
using Pack = stdx::native_simd<double>;
using PackMask = Pack::mask_type;
// Four doubles handled as one (a weight and its gradient): one AVX2 register, two SSE2 ones.
using Quad = stdx::fixed_size_simd<double, 4>;

}  // namespace anode

namespace Eigen {

// Pack as the scalar of Eigen's matrices (element-wise arithmetic, no vectorisation of its own).
template <>
struct NumTraits<anode::Pack> : GenericNumTraits<anode::Pack> {
  using Real = anode::Pack;
  using NonInteger = anode::Pack;
  using Nested = anode::Pack;
  using Literal = double;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 0,
    ReadCost = 1,
    AddCost = 1,
    MulCost = 1
  };
  static anode::Pack epsilon() { return anode::Pack(std::numeric_limits<double>::epsilon()); }
  static anode::Pack dummy_precision() { return anode::Pack(1e-12); }
  static int digits10() { return std::numeric_limits<double>::digits10; }
};

}  // namespace Eigen

namespace anode {

template <class S>
using Mat3Of = Eigen::Matrix<S, 3, 3>;
template <class S>
using Vec3Of = Eigen::Matrix<S, 3, 1>;
using Mat3Pack = Mat3Of<Pack>;

// What the equations need of a scalar, for double and for Pack alike.
inline double sqrtOf(double x) {
  return std::sqrt(x);
}
inline Pack sqrtOf(const Pack& x) {
  return stdx::sqrt(x);
}
inline double powOf(double x, double y) {
  return std::pow(x, y);
}
inline Pack powOf(const Pack& x, double y) {
  return stdx::pow(x, Pack(y));
}
inline double expOf(double x) {
  return std::exp(x);
}
inline Pack expOf(const Pack& x) {
  return stdx::exp(x);
}
inline double absOf(double x) {
  return std::abs(x);
}
inline Pack absOf(const Pack& x) {
  return stdx::abs(x);
}
inline double maxOf(double a, double b) {
  return std::max(a, b);
}
inline Pack maxOf(const Pack& a, const Pack& b) {
  return stdx::max(a, b);
}
// a where the condition holds, b elsewhere.
inline double select(bool condition, double a, double b) {
  return condition ? a : b;
}
inline Pack select(const PackMask& condition, const Pack& a, const Pack& b) {
  Pack r = b;
  stdx::where(condition, r) = a;
  return r;
}
inline bool anyOf(bool condition) {
  return condition;
}
inline bool anyOf(const PackMask& condition) {
  return stdx::any_of(condition);
}

// The Frobenius norm summed in index order (Eigen's own reduction sums in packets of the vector
// width, which would tie the result to the instruction set).
template <class S>
S frobeniusNorm(const Mat3Of<S>& m) {
  S sum = m(0) * m(0);
  for (int k = 1; k < 9; ++k) sum = sum + m(k) * m(k);
  return sqrtOf(sum);
}

// Lane l of a pack of matrices, and back.
inline Mat3 lane(const Mat3Pack& m, int l) {
  Mat3 out;
  for (int k = 0; k < 9; ++k) out(k) = m(k)[l];
  return out;
}
inline void setLane(Mat3Pack& m, int l, const Mat3& value) {
  for (int k = 0; k < 9; ++k) m(k)[l] = value(k);
}
inline void setLane(Vec3Of<Pack>& v, int l, const Vec3& value) {
  for (int k = 0; k < 3; ++k) v(k)[l] = value(k);
}

}  // namespace anode
