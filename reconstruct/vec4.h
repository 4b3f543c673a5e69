// Pixel vectors of the iterative solvers: RGB stored as 4 floats (the 4th lane is 0),
// one 16-byte SIMD register per pixel (GCC/Clang vector extension; SSE2 on x86-64).
// Reductions are accumulated in double lanes (Vec4d).
#pragma once

#include <cstddef>
#include <vector>

#include "core/image.h"

namespace dp::reconstruct {

typedef float Vec4 __attribute__((vector_size(16)));
typedef double Vec2d __attribute__((vector_size(16)));

// Four double lanes as two 16-byte halves (a 32-byte vector type would change the ABI
// depending on AVX).
struct Vec4d {
  Vec2d lo = {}, hi = {};
  double operator[](int c) const { return c < 2 ? lo[c] : hi[c - 2]; }
  Vec4d& operator+=(const Vec4d& o) {
    lo += o.lo;
    hi += o.hi;
    return *this;
  }
};

// acc += v, lane by lane in double.
inline void accumulate(Vec4d& acc, Vec4 v) {
  acc.lo += Vec2d{double(v[0]), double(v[1])};
  acc.hi += Vec2d{double(v[2]), double(v[3])};
}
inline Vec4 to_vec4(const Rgb& c) { return Vec4{c[0], c[1], c[2], 0.0f}; }
inline Rgb to_rgb(Vec4 v) { return Rgb(v[0], v[1], v[2]); }

// RGB-interleaved floats (3 per pixel) <-> Vec4 per pixel.
inline std::vector<Vec4> to_vec4(const std::vector<float>& rgb) {
  std::vector<Vec4> out(rgb.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec4{rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 0.0f};
  return out;
}

}  // namespace dp::reconstruct
