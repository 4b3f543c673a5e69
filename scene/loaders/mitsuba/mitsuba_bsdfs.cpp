// Mitsuba BSDFs -> scene/bsdf/bsdfs.h factories. Defaults are Mitsuba's.
//   diffuse          reflectance (0.5); one-sided like Mitsuba's (black from behind)
//   roughdiffuse     read as diffuse with a warning (Oren-Nayar roughness dropped)
//   twosided         one nested BSDF; around a transmissive BSDF (dielectric, ...) the
//                    wrapper is dropped with a warning (those already have two sides);
//                    two different nested BSDFs are an error
//   conductor, roughconductor
//                    material (Cu) or eta/k (spectra or RGB), ext_eta (1), 
//                    specular_reflectance (1); rough: distribution beckmann (default) |
//                    ggx (phong -> beckmann with the same alpha, with a warning), alpha
//                    (0.1) or alpha_u/alpha_v
//   dielectric, roughdielectric, thindielectric
//                    int_ior (bk7), ext_ior (air) as numbers or names,
//                    specular_reflectance/transmittance (not thindielectric); rough:
//                    distribution, isotropic alpha only
//   plastic, roughplastic
//                    diffuse_reflectance (0.5), specular_reflectance (1), int_ior
//                    (polypropylene), ext_ior (air), nonlinear (false); rough:
//                    distribution, alpha (0.1)
//   phong            exponent (30), specular_reflectance (0.2), diffuse_reflectance (0.5)
//   null, mask       mask: opacity (0.5) as a stochastic pass-through + nested BSDF
//   bumpmap, normalmap
//                    not implemented: the nested BSDF is used with the unperturbed
//                    normal, with one warning naming the plugin
// sample_visible is ignored with a warning (it only changes the sampling technique).
#include "core/error.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"
#include "scene/loaders/mitsuba/spectrum.h"

namespace dp::scene::mitsuba {

namespace {

constexpr float kAir = 1.000277f, kBk7 = 1.5046f, kPolypropylene = 1.49f;

MicrofacetType distribution(Object& o) {
  const XmlElement* at = o.take("distribution");
  const std::string d = o.get_string("distribution", "beckmann");
  if (d == "beckmann") return MicrofacetType::beckmann;
  if (d == "ggx") return MicrofacetType::ggx;
  if (d == "phong") {
    o.loader().warn(*at, "microfacet distribution 'phong' approximated by 'beckmann' with the same alpha");
    return MicrofacetType::beckmann;
  }
  o.error_at(at ? *at : o.elem(), "unsupported microfacet distribution '" + quote_input(d) + "' (beckmann, ggx)");
}

void alphas(Object& o, float& au, float& av) {
  if (o.has("alpha_u") || o.has("alpha_v")) {
    if (o.has("alpha")) o.error("give either 'alpha' or 'alpha_u'/'alpha_v', not both");
    au = o.get_float("alpha_u", 0.1f);
    av = o.get_float("alpha_v", 0.1f);
  } else {
    au = av = o.get_float("alpha", 0.1f);
  }
  if (!(au >= 0.0f) || !(av >= 0.0f)) o.value_error_at(o.elem(), "roughness alpha must be >= 0");
  o.ignore("sample_visible", "sampling technique only");
}

BsdfPtr nested_one(Loader& ld, Object& o) {
  const std::vector<const XmlElement*> inner = o.objects("bsdf");
  if (inner.size() != 1) o.error(o.describe() + " needs exactly one nested <bsdf> (got " + std::to_string(inner.size()) + ")");
  return ld.bsdf(*inner[0]);
}

BsdfPtr conductor(Object& o, bool rough) {
  float au = 0, av = 0;
  MicrofacetType dist = MicrofacetType::beckmann;
  if (rough) {
    dist = distribution(o);
    alphas(o, au, av);
  }
  const XmlElement* mat_at = o.take("material");
  const std::string material = o.get_string("material", "Cu");
  const std::optional<ConductorIor> named = named_conductor(material);
  if (!named)
    o.error_at(mat_at ? *mat_at : o.elem(), "unknown conductor material '" + quote_input(material) + "' (" + conductor_names() + ")");
  ConductorFresnel f;
  if (material == "none" && !o.has("eta") && !o.has("k")) {
    f.kind = ConductorFresnel::Kind::schlick;  // Mitsuba's "none": a perfect mirror
    f.f0 = Rgb::Ones();
  } else {
    if (mat_at && (o.has("eta") || o.has("k"))) o.error("give either 'material' or 'eta'/'k', not both");
    const float ext = o.get_ior("ext_eta", 1.0f);
    f.kind = ConductorFresnel::Kind::complex;
    f.eta = o.get_rgb("eta", named->eta) / ext;
    f.k = o.get_rgb("k", named->k) / ext;
    if (!(f.eta > 0.0f).all() || !(f.k >= 0.0f).all()) o.value_error_at(o.elem(), "conductor eta must be > 0 and k >= 0");
  }
  return make_conductor(au, av, dist, f, o.get_texture("specular_reflectance"));
}

BsdfPtr dielectric(Object& o, const std::string& type) {
  float int_ior = kBk7;
  if (const XmlElement* m = o.take("material")) {  // non-Mitsuba <material value="bk7"/>
    const std::optional<float> ior = named_ior(o.value_of(*m));
    if (!ior) o.error_at(*m, "unknown index of refraction '" + o.value_of(*m) + "'");
    int_ior = *ior;
  }
  int_ior = o.get_ior("int_ior", int_ior);
  const float ext_ior = o.get_ior("ext_ior", kAir);
  if (type == "thindielectric") return make_thin_dielectric(int_ior, ext_ior);
  float au = 0, av = 0;
  MicrofacetType dist = MicrofacetType::beckmann;
  if (type == "roughdielectric") {
    dist = distribution(o);
    alphas(o, au, av);
    if (au != av) o.error("anisotropic roughdielectric (alpha_u != alpha_v) is not supported");
  }
  TexturePtr sr = o.get_texture("specular_reflectance"), st = o.get_texture("specular_transmittance");
  return make_dielectric(int_ior, ext_ior, au, dist, sr, st);
}

BsdfPtr plastic(Object& o, bool rough) {
  float au = 0, av = 0;
  MicrofacetType dist = MicrofacetType::beckmann;
  if (rough) {
    dist = distribution(o);
    alphas(o, au, av);
    if (au != av) o.error("anisotropic roughplastic is not supported");
  }
  TexturePtr kd = o.get_texture("diffuse_reflectance", Rgb::Constant(0.5f));
  TexturePtr ks = o.get_texture("specular_reflectance");
  const float int_ior = o.get_ior("int_ior", kPolypropylene), ext_ior = o.get_ior("ext_ior", kAir);
  const bool nonlinear = o.get_bool("nonlinear", false);
  return make_plastic(kd, int_ior, ext_ior, au, dist, nonlinear, ks);
}

}  // namespace

BsdfPtr build_bsdf(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  const std::string t = o.type();
  BsdfPtr b;
  if (t == "diffuse" || t == "roughdiffuse") {
    if (t == "roughdiffuse") {
      ld.warn(e, "roughdiffuse read as diffuse (its Oren-Nayar roughness is not implemented)");
      o.take("alpha");
      o.take("use_fast_approx");
    }
    b = make_diffuse(o.get_texture("reflectance", Rgb::Constant(0.5f)));
  } else if (t == "twosided") {
    const std::vector<const XmlElement*> inner = o.objects("bsdf");
    if (inner.size() != 1) o.error("twosided needs exactly one nested <bsdf> (different front and back BSDFs are not supported)");
    BsdfPtr in = ld.bsdf(*inner[0]);
    if (in->lobes() & kTransmission) {
      ld.warn(e, "twosided around the transmissive '" + quote_input(in->name()) + "' dropped (it already has two sides)");
      b = in;
    } else {
      b = make_two_sided(in);
    }
  } else if (t == "conductor" || t == "roughconductor") {
    b = conductor(o, t == "roughconductor");
  } else if (t == "dielectric" || t == "roughdielectric" || t == "thindielectric") {
    b = dielectric(o, t);
  } else if (t == "plastic" || t == "roughplastic") {
    b = plastic(o, t == "roughplastic");
  } else if (t == "phong") {
    const float n = o.get_float("exponent", 30.0f);
    if (!(n >= 0.0f)) o.value_error_at(e, "phong 'exponent' must be >= 0");
    b = make_phong(o.get_texture("diffuse_reflectance", Rgb::Constant(0.5f)),
                   o.get_texture("specular_reflectance", Rgb::Constant(0.2f)), n);
  } else if (t == "null") {
    b = make_null();
  } else if (t == "mask") {
    TexturePtr opacity = o.get_texture("opacity", Rgb::Constant(0.5f));
    b = make_mask(nested_one(ld, o), opacity);
  } else if (t == "bumpmap" || t == "normalmap") {
    ld.warn(e, t + " is not implemented: the nested BSDF is shaded with the unperturbed normal");
    (void)o.objects("texture");
    o.take("normalmap");
    o.take("scale");
    b = nested_one(ld, o);
  } else {
    o.error("unsupported bsdf type '" + t +
            "' (diffuse, roughdiffuse, twosided, conductor, roughconductor, dielectric, roughdielectric, "
            "thindielectric, plastic, roughplastic, phong, null, mask, bumpmap, normalmap)");
  }
  o.finish();
  return b;
}

}  // namespace dp::scene::mitsuba
