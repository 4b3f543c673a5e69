// Basic math types for Deltapath: Eigen vectors, RGB spectra, orthonormal frames.
// Geometry and throughput are float; Jacobians, Newton steps and accumulators are
// double (see DESIGN.md, Numerics).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace dp {

using Vec2 = Eigen::Vector2f;
using Vec3 = Eigen::Vector3f;
using Vec2d = Eigen::Vector2d;
using Vec3d = Eigen::Vector3d;
using Vec2i = Eigen::Vector2i;
using Mat3 = Eigen::Matrix3f;
using Mat4 = Eigen::Matrix4f;
using Mat4d = Eigen::Matrix4d;

// Linear RGB (Rec. 709 primaries), component-wise arithmetic.
using Rgb = Eigen::Array3f;
using Rgbd = Eigen::Array3d;

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv2Pi = 0.15915494309189533577f;
constexpr float kInv4Pi = 0.07957747154594766788f;
constexpr double kPiD = 3.14159265358979323846;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline float sqr(float x) { return x * x; }
inline double sqr(double x) { return x * x; }
inline float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
inline double safe_sqrt(double x) { return std::sqrt(std::max(0.0, x)); }
inline float deg_to_rad(float d) { return d * (kPi / 180.0f); }

inline bool is_finite(const Rgb& c) { return c.isFinite().all(); }
inline bool is_black(const Rgb& c) { return (c == 0.0f).all(); }
inline float luminance(const Rgb& c) { return 0.212671f * c[0] + 0.715160f * c[1] + 0.072169f * c[2]; }
inline float max_component(const Rgb& c) { return c.maxCoeff(); }

// Mirror reflection of w about n (both pointing away from the surface).
inline Vec3 reflect(const Vec3& w, const Vec3& n) { return 2.0f * w.dot(n) * n - w; }

// Orthonormal frame; `n` is the local +z axis. Local coordinates: (s, t, n).
struct Frame {
  Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

  Frame() = default;
  Frame(const Vec3& s_, const Vec3& t_, const Vec3& n_) : s(s_), t(t_), n(n_) {}

  // Branchless ONB (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
  static Frame from_normal(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z());
    const float a = -1.0f / (sign + n.z());
    const float b = n.x() * n.y() * a;
    return Frame(Vec3(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x()),
                 Vec3(b, sign + n.y() * n.y() * a, -n.y()), n);
  }
  // Frame with n and the s axis as close as possible to `tangent` (Gram-Schmidt).
  static Frame from_normal_tangent(const Vec3& n, const Vec3& tangent) {
    Vec3 s = tangent - n * n.dot(tangent);
    const float len = s.norm();
    if (!(len > 1e-8f)) return from_normal(n);
    s /= len;
    return Frame(s, n.cross(s), n);
  }

  Vec3 to_local(const Vec3& v) const { return Vec3(v.dot(s), v.dot(t), v.dot(n)); }
  Vec3 to_world(const Vec3& v) const { return s * v.x() + t * v.y() + n * v.z(); }
};

// Local-frame trigonometry (z = normal).
inline float cos_theta(const Vec3& w) { return w.z(); }
inline float abs_cos_theta(const Vec3& w) { return std::abs(w.z()); }
inline float cos2_theta(const Vec3& w) { return w.z() * w.z(); }
inline float sin2_theta(const Vec3& w) { return std::max(0.0f, 1.0f - cos2_theta(w)); }
inline float tan2_theta(const Vec3& w) { return sin2_theta(w) / cos2_theta(w); }
inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z() * b.z() > 0.0f; }

struct Ray {
  Vec3 o;
  Vec3 d;          // unit length
  float tmin = 0;  // parametric range [tmin, tmax]
  float tmax = kInfinity;
  Vec3 at(float t) const { return o + t * d; }
};

struct Bounds3 {
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi{-kInfinity, -kInfinity, -kInfinity};
  void expand(const Vec3& p) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  void expand(const Bounds3& b) { lo = lo.cwiseMin(b.lo); hi = hi.cwiseMax(b.hi); }
  bool valid() const { return (lo.array() <= hi.array()).all(); }
  Vec3 center() const { return 0.5f * (lo + hi); }
  float diagonal() const { return valid() ? (hi - lo).norm() : 0.0f; }
};

}  // namespace dp
