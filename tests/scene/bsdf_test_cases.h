// Shared fixtures for the BSDF tests: the catalogue of BSDF configurations (every
// factory in scene/bsdf/bsdfs.h, several roughnesses, both distributions, anisotropic) and
// incident directions (including grazing ones and, for dielectrics, both sides).
#pragma once

#include <string>
#include <vector>

#include "core/rng.h"
#include "scene/bsdf/bsdfs.h"

namespace dp::test {

struct BsdfCase {
  std::string name;        // human-readable configuration, printed on failure
  scene::BsdfPtr bsdf;
  bool two_sided_dir = false;  // also test wi below the surface (dielectrics, two-sided)
  bool reflection_only = true; // reciprocity eval(wi,wo) == eval(wo,wi) applies
  float ggx_eta = 0;           // int_ior / ext_ior for GGX rough dielectrics (chi-square warp)
  float alpha = 0;             // microfacet alpha (chi-square warp)
  float eta = 0;               // int_ior / ext_ior of rough dielectrics (reciprocity test)
};

// Every BSDF configuration under test (constructed once; rough plastics precompute
// tables).
const std::vector<BsdfCase>& bsdf_cases();

// Incident direction with cos(theta) = cos_t at azimuth phi (radians).
Vec3 dir_from(float cos_t, float phi);

// Incident directions for a case: upper hemisphere cosines {1, 0.7, 0.3, 0.05} (0.05
// is 87 degrees), plus their mirrored versions for two-sided cases.
std::vector<Vec3> incident_dirs(const BsdfCase& c);

// Monte Carlo estimate of the directional albedo \int f |cos wo| dwo (+ delta lobes)
// from sample() weights (max over RGB channels of the mean), with its standard error.
struct AlbedoEstimate {
  double mean = 0, std_error = 0;
};
AlbedoEstimate albedo_by_sampling(const scene::Bsdf& bsdf, const scene::BsdfContext& ctx, const Vec3& wi,
                                  int samples, uint64_t seed);
// The same integral estimated independently of sample()/pdf(): uniform sphere
// directions weighted by eval |cos| 4 pi (non-delta lobes only).
AlbedoEstimate albedo_by_uniform(const scene::Bsdf& bsdf, const scene::BsdfContext& ctx, const Vec3& wi,
                                 int samples, uint64_t seed);

}  // namespace dp::test
