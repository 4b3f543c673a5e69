// BSDF interface. Contract:
//  * All directions are in the local shading frame (z = shading normal), unit length,
//    pointing away from the surface: `wi` toward the previous vertex on the camera side
//    of the path, `wo` toward the next vertex (the light side).
//  * eval() returns f(wi, wo) WITHOUT the cosine factor; Dirac (delta) lobes are not
//    included (they evaluate to 0).
//  * pdf() is the solid-angle density of sample() producing wo, over its non-delta lobes
//    (including the lobe-selection probability).
//  * eval_pdf() returns eval() and stores pdf() in pdf_out: the same two values, in one
//    call (next-event estimation with MIS needs both; microfacet BSDFs share h, D and
//    G1(wi) between them, Phong its pow()).
//  * sample() returns wo, weight = f(wi,wo) |cos(wo)| / pdf, and for a delta lobe
//    pdf = the discrete probability of choosing that lobe (weight includes 1/pdf).
//  * roughness(): the lowest microfacet alpha over the non-delta components (0 if the
//    BSDF only has delta lobes, +inf for purely diffuse). Used by the vertex
//    classification of shift mappings (connectable vs glossy/specular).
//  * TransportMode::radiance for paths traced from the camera; importance for paths
//    traced from lights (changes refraction scaling by 1/eta^2, Veach 1997 Sec. 5.2).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "core/math.h"

namespace dp::scene {

enum class TransportMode : uint8_t { radiance, importance };

// Lobe flags (bit set).
enum LobeFlags : uint32_t {
  kDiffuseReflection = 1u << 0,
  kGlossyReflection = 1u << 1,
  kGlossyTransmission = 1u << 2,
  kDeltaReflection = 1u << 3,
  kDeltaTransmission = 1u << 4,
  kNull = 1u << 5,  // pass-through (mask opacity), direction unchanged
  kDelta = kDeltaReflection | kDeltaTransmission | kNull,
  kGlossy = kGlossyReflection | kGlossyTransmission,
  kTransmission = kGlossyTransmission | kDeltaTransmission | kNull,
};

struct BsdfContext {
  Vec2 uv{0, 0};  // surface texture coordinates
  TransportMode mode = TransportMode::radiance;
};

struct BsdfSample {
  Vec3 wo{0, 0, 1};
  Rgb weight = Rgb::Zero();  // f |cos wo| / pdf
  float pdf = 0;             // solid angle, or discrete lobe probability for delta lobes
  float eta = 1;             // relative index of refraction eta_o/eta_i (1 for reflection)
  uint32_t lobe = 0;         // the single LobeFlags bit that was sampled
  bool is_delta() const { return (lobe & kDelta) != 0; }
};

class Bsdf {
 public:
  virtual ~Bsdf() = default;
  virtual Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const = 0;
  virtual float pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const = 0;
  virtual Rgb eval_pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const {
    pdf_out = pdf(ctx, wi, wo);
    return eval(ctx, wi, wo);
  }
  // u_lobe selects among components, u drives the chosen component's 2D warp.
  virtual std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                           const Vec2& u) const = 0;
  virtual float roughness() const = 0;
  // Phong exponent n of a (normalized modified) Phong lobe, 0 for every other BSDF; the
  // shift-mapping classification treats n above a threshold as glossy
  // (SCENE_FORMAT.md: "roughness < 0.05 or phong exponent > 100 is not connectable").
  virtual float phong_exponent() const { return 0.0f; }
  virtual uint32_t lobes() const = 0;  // union of LobeFlags
  virtual std::string name() const = 0;
  // Diffuse-like reflectance for feature buffers (structure-adaptive kernels).
  virtual Rgb albedo(const BsdfContext& ctx) const { (void)ctx; return Rgb::Zero(); }
  virtual bool has_texture() const { return false; }

  bool has_delta() const { return (lobes() & kDelta) != 0; }
  bool is_purely_delta() const { return (lobes() & ~uint32_t(kDelta)) == 0; }
  bool has_glossy() const { return (lobes() & kGlossy) != 0; }
};

using BsdfPtr = std::shared_ptr<const Bsdf>;

constexpr float kDiffuseRoughness = std::numeric_limits<float>::infinity();

}  // namespace dp::scene
