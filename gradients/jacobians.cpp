#include "gradients/jacobians.h"

#include <cmath>

namespace dp::gradients {

double reconnection_jacobian(const Vec3d& base_prev, const Vec3d& offset_prev, const Vec3d& target,
                             const Vec3d& target_normal) {
  const Vec3d db = base_prev - target, dof = offset_prev - target;
  const double lb2 = db.squaredNorm(), lo2 = dof.squaredNorm();
  if (!(lb2 > 0.0) || !(lo2 > 0.0)) return 0.0;
  const double cos_b = std::abs(target_normal.dot(db)) / std::sqrt(lb2);
  const double cos_o = std::abs(target_normal.dot(dof)) / std::sqrt(lo2);
  if (!(cos_b > 0.0)) return 0.0;
  return (cos_o * lb2) / (cos_b * lo2);
}

Vec3d reflection_half_vector(const Vec3d& wi, const Vec3d& wo) { return (wi + wo).normalized(); }

Vec3d reflect_about(const Vec3d& wi, const Vec3d& h) { return 2.0 * wi.dot(h) * h - wi; }

double reflection_jacobian(const Vec3d& wo, const Vec3d& wo_offset, const Vec3d& h) {
  const double base = std::abs(wo.dot(h));
  return base > 0.0 ? std::abs(wo_offset.dot(h)) / base : 0.0;
}

std::optional<Vec3d> refraction_half_vector(const Vec3d& wi, const Vec3d& wo, double eta) {
  if (!(std::abs(eta - 1.0) > 1e-7)) return std::nullopt;  // index-matched: h is undefined
  Vec3d H = wi + eta * wo;
  const double len = H.norm();
  if (!(len > 0.0)) return std::nullopt;
  H /= len;
  return H.z() < 0.0 ? Vec3d(-H) : H;
}

std::optional<Vec3d> refract_about(const Vec3d& wi, const Vec3d& h, double eta) {
  const double c = wi.dot(h);
  const double sin2_t = (1.0 - c * c) / (eta * eta);
  if (sin2_t >= 1.0) return std::nullopt;  // total internal reflection
  const double cos_t = std::copysign(std::sqrt(1.0 - sin2_t), -c);
  return Vec3d((c / eta + cos_t) * h - wi / eta);
}

double refraction_jacobian(const Vec3d& wi, const Vec3d& wo, const Vec3d& wi_offset, const Vec3d& wo_offset,
                           double eta) {
  const Vec3d H = wi + eta * wo, Ho = wi_offset + eta * wo_offset;
  const double h2 = H.squaredNorm();
  if (!(h2 > 0.0)) return 0.0;
  const Vec3d h = H / std::sqrt(h2);
  const double denom = std::abs(wo_offset.dot(h));
  if (!(denom > 0.0)) return 0.0;
  return (Ho.squaredNorm() / h2) * std::abs(wo.dot(h)) / denom;
}

}  // namespace dp::gradients
