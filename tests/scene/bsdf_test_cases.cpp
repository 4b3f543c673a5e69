#include "tests/scene/bsdf_test_cases.h"

#include "core/warp.h"

namespace dp::test {

using namespace dp::scene;

namespace {
TexturePtr c(float v) { return constant_texture(Rgb::Constant(v)); }
TexturePtr c3(float r, float g, float b) { return constant_texture(Rgb(r, g, b)); }
const char* dname(MicrofacetType t) { return t == MicrofacetType::ggx ? "ggx" : "beckmann"; }

std::vector<BsdfCase> build() {
  std::vector<BsdfCase> v;
  v.push_back({"diffuse", make_diffuse(c3(0.8f, 0.5f, 0.2f)), false, true});
  v.push_back({"twosided(diffuse)", make_two_sided(make_diffuse(c(0.7f))), true, true});
  for (float n : {1.0f, 20.0f, 300.0f})
    v.push_back({"phong n=" + std::to_string(n), make_phong(c(0.3f), c(0.6f), n), false, true});
  v.push_back({"phong specular-only n=40", make_phong(c(0.0f), c(1.0f), 40.0f), false, true});
  v.push_back({"mirror", make_mirror(c(0.9f)), false, true});
  v.push_back({"dielectric 1.5", make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx), true, false});
  v.push_back({"thindielectric 1.5", make_thin_dielectric(1.5f, 1.0f), true, false});
  v.push_back({"null", make_null(), true, false});
  ConductorFresnel gold;  // complex index of gold (approximate RGB values)
  gold.kind = ConductorFresnel::Kind::complex;
  gold.eta = Rgb(0.143f, 0.374f, 1.442f);
  gold.k = Rgb(3.983f, 2.385f, 1.603f);
  ConductorFresnel schlick;
  schlick.f0 = Rgb(0.95f, 0.64f, 0.54f);
  v.push_back({"conductor smooth", make_conductor(0, 0, MicrofacetType::ggx, gold), false, true});
  for (MicrofacetType t : {MicrofacetType::beckmann, MicrofacetType::ggx}) {
    for (float a : {0.05f, 0.2f, 0.6f, 1.0f})
      v.push_back({std::string("conductor ") + dname(t) + " a=" + std::to_string(a),
                   make_conductor(a, a, t, a < 0.5f ? gold : schlick), false, true});
    v.push_back({std::string("conductor aniso ") + dname(t) + " 0.05x0.4", make_conductor(0.05f, 0.4f, t, schlick),
                 false, true});
    v.push_back({std::string("conductor aniso ") + dname(t) + " 0.7x0.1", make_conductor(0.7f, 0.1f, t, gold),
                 false, true});
    for (float a : {0.05f, 0.3f, 1.0f})
      v.push_back({std::string("roughdielectric ") + dname(t) + " a=" + std::to_string(a),
                   make_dielectric(1.5f, 1.0f, a, t), true, false,
                   t == MicrofacetType::ggx ? 1.5f : 0.0f, a, 1.5f});
    for (float a : {0.05f, 0.3f, 1.0f})
      v.push_back({std::string("roughplastic ") + dname(t) + " a=" + std::to_string(a),
                   make_plastic(c3(0.8f, 0.4f, 0.1f), 1.5f, 1.0f, a, t, a > 0.5f), false, true});
  }
  v.push_back({"twosided(roughconductor ggx a=0.3)",
               make_two_sided(make_conductor(0.3f, 0.3f, MicrofacetType::ggx, schlick)), true, true});
  v.push_back({"plastic smooth", make_plastic(c3(0.8f, 0.4f, 0.1f), 1.5f, 1.0f, 0.0f, MicrofacetType::ggx),
               false, true});
  v.push_back({"plastic smooth nonlinear",
               make_plastic(c(0.9f), 1.33f, 1.0f, 0.0f, MicrofacetType::ggx, true, c(0.5f)), false, true});
  v.push_back({"mask(roughconductor beckmann a=0.2)",
               make_mask(make_conductor(0.2f, 0.2f, MicrofacetType::beckmann, schlick), c3(0.3f, 0.5f, 0.7f)), false,
               false});
  v.push_back({"mask(diffuse)", make_mask(make_diffuse(c(0.5f)), c(0.6f)), false, false});
  return v;
}
}  // namespace

const std::vector<BsdfCase>& bsdf_cases() {
  static const std::vector<BsdfCase> cases = build();
  return cases;
}

Vec3 dir_from(float cos_t, float phi) {
  const float s = safe_sqrt(1.0f - cos_t * cos_t);
  return Vec3(s * std::cos(phi), s * std::sin(phi), cos_t);
}

std::vector<Vec3> incident_dirs(const BsdfCase& c) {
  std::vector<Vec3> out;
  const float cosines[] = {1.0f, 0.7f, 0.3f, 0.05f};
  for (int k = 0; k < 4; ++k) out.push_back(dir_from(cosines[k], 0.4f + 1.3f * float(k)));
  if (c.two_sided_dir)
    for (int k = 0; k < 4; ++k) out.push_back(dir_from(-cosines[k], 2.0f + 0.9f * float(k)));
  return out;
}

namespace {
AlbedoEstimate finish(const Rgbd& sum, const Rgbd& sum2, int n) {
  int best = 0;
  for (int ch = 1; ch < 3; ++ch)
    if (sum[ch] > sum[best]) best = ch;
  AlbedoEstimate e;
  e.mean = sum[best] / n;
  const double var = std::max(0.0, sum2[best] / n - e.mean * e.mean);
  e.std_error = std::sqrt(var / (n - 1));
  return e;
}
}  // namespace

AlbedoEstimate albedo_by_sampling(const Bsdf& bsdf, const BsdfContext& ctx, const Vec3& wi, int samples,
                                  uint64_t seed) {
  core::Rng rng(seed, 7);
  Rgbd sum = Rgbd::Zero(), sum2 = Rgbd::Zero();
  for (int k = 0; k < samples; ++k) {
    const float ul = rng.uniform();
    const auto s = bsdf.sample(ctx, wi, ul, rng.uniform2());
    if (!s) continue;
    const Rgbd w = s->weight.cast<double>();
    sum += w;
    sum2 += w * w;
  }
  return finish(sum, sum2, samples);
}

AlbedoEstimate albedo_by_uniform(const Bsdf& bsdf, const BsdfContext& ctx, const Vec3& wi, int samples,
                                 uint64_t seed) {
  core::Rng rng(seed, 11);
  Rgbd sum = Rgbd::Zero(), sum2 = Rgbd::Zero();
  for (int k = 0; k < samples; ++k) {
    const Vec3 wo = core::warp::square_to_uniform_sphere(rng.uniform2());
    const Rgbd w = (bsdf.eval(ctx, wi, wo) * (std::abs(wo.z()) * 4.0f * kPi)).cast<double>();
    sum += w;
    sum2 += w * w;
  }
  return finish(sum, sum2, samples);
}

}  // namespace dp::test
