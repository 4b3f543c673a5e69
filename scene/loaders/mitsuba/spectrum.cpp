// Spectrum -> RGB conversion and named indices of refraction (contract in spectrum.h).
#include "scene/loaders/mitsuba/spectrum.h"

#include <array>
#include <cmath>

namespace dp::scene {

namespace {

// Piecewise Gaussian lobe with different widths left and right of the peak.
double lobe(double nm, double mu, double sigma_left, double sigma_right) {
  const double t = (nm - mu) / (nm < mu ? sigma_left : sigma_right);
  return std::exp(-0.5 * t * t);
}

Vec3d cie_xyz_d(double nm) {
  // Wyman, Sloan and Shirley 2013, "Simple Analytic Approximations to the CIE XYZ
  // Color Matching Functions", JCGT 2(2), Eq. 2 (multi-lobe fit, the more accurate of
  // the paper's two fits; max error ~1% of the peak of each curve).
  const double x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
                   0.065 * lobe(nm, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
  return Vec3d(x, y, z);
}

Vec3d xyz_to_rgb_d(const Vec3d& c) {
  // XYZ -> linear sRGB / Rec. 709 primaries, D65 white (IEC 61966-2-1, the inverse of
  // its RGB -> XYZ matrix).
  return Vec3d(3.2404542 * c.x() - 1.5371385 * c.y() - 0.4985314 * c.z(),
               -0.9692660 * c.x() + 1.8760108 * c.y() + 0.0415560 * c.z(),
               0.0556434 * c.x() - 0.2040259 * c.y() + 1.0572252 * c.z());
}

constexpr double kLambdaMin = 360.0, kLambdaMax = 830.0, kStep = 1.0;

template <typename F>
Vec3d integrate_xyz(F&& spectrum) {
  Vec3d sum = Vec3d::Zero();
  for (double nm = kLambdaMin; nm <= kLambdaMax + 1e-9; nm += kStep) {
    const double w = (nm == kLambdaMin || nm + kStep > kLambdaMax + 1e-9) ? 0.5 : 1.0;  // trapezoid
    sum += w * spectrum(nm) * cie_xyz_d(nm);
  }
  return sum * kStep;
}

const Vec3d& flat_rgb() {
  static const Vec3d rgb = xyz_to_rgb_d(integrate_xyz([](double) { return 1.0; }));
  return rgb;
}

struct ConductorTableEntry {
  const char* name;
  std::array<float, 3> eta, k;
};

// RGB complex indices of refraction of Mitsuba's named conductors.
// Source data: the spectral n(lambda), k(lambda) tables Mitsuba 0.6 ships in
// data/ior/<name>.eta.spd / <name>.k.spd (from the luxpop.com optical-constants
// database; the *_palik variants from Palik 1985, "Handbook of Optical Constants of
// Solids"), roughly 300..890 nm.
// Derivation: each of n and k was projected separately with spectrum_to_rgb() above
// (piecewise-linear spectrum x CIE 1931 fit -> XYZ -> linear Rec. 709, white-balanced
// so that a flat spectrum stays flat), printed with 6 significant digits.
// Approximation: projecting n and k to RGB and evaluating the Fresnel equations per
// channel is not the RGB of the spectral reflectance (the Fresnel term is nonlinear in
// n, k); errors are largest for strongly dispersive metals (Cu, Au). Exporters that
// skip the white balance (e.g. the eta/k written into Bitterli's scene files) give the
// same numbers times the RGB of the equal-energy white, (1.205, 0.948, 0.909).
const ConductorTableEntry kConductors[] = {
      {"Ag", {0.128755f, 0.123146f, 0.152181f}, {3.99871f, 3.29896f, 2.36061f}},
      {"Al", {1.36921f, 0.932635f, 0.572798f}, {7.6438f, 6.62049f, 5.3188f}},
      {"AlAs", {2.99278f, 3.40724f, 2.43969f}, {0.000483652f, -0.000450115f, 0.00811865f}},
      {"AlAs_palik", {2.99278f, 3.40724f, 2.43969f}, {0.000483652f, -0.000450115f, 0.00811865f}},
      {"AlSb", {3.91903f, 4.27885f, 5.04213f}, {-0.0225283f, 0.0968605f, 1.43014f}},
      {"AlSb_palik", {3.91903f, 4.27885f, 5.04213f}, {-0.0225283f, 0.0968605f, 1.43014f}},
      {"Au", {0.121317f, 0.392611f, 1.58682f}, {3.29635f, 2.52239f, 1.76216f}},
      {"Be", {3.47274f, 3.3597f, 3.06188f}, {3.18265f, 3.17477f, 3.15529f}},
      {"Be_palik", {3.47274f, 3.3597f, 3.06188f}, {3.18265f, 3.17477f, 3.15529f}},
      {"Cr", {3.62069f, 3.08092f, 1.81933f}, {4.32105f, 4.46219f, 4.13f}},
      {"CsI", {1.78032f, 1.79514f, 1.82831f}, {0.0f, 0.0f, 0.0f}},
      {"CsI_palik", {1.78032f, 1.79514f, 1.82831f}, {0.0f, 0.0f, 0.0f}},
      {"Cu", {0.169671f, 0.970876f, 1.21283f}, {3.23633f, 2.59374f, 2.35543f}},
      {"Cu2O", {2.94964f, 3.10969f, 3.02691f}, {0.0957374f, 0.203481f, 0.666486f}},
      {"Cu2O_palik", {2.94964f, 3.10969f, 3.02691f}, {0.0957374f, 0.203481f, 0.666486f}},
      {"CuO", {2.69308f, 2.58281f, 2.4307f}, {0.434468f, 0.599719f, 0.794374f}},
      {"CuO_palik", {2.69308f, 2.58281f, 2.4307f}, {0.434468f, 0.599719f, 0.794374f}},
      {"Cu_palik", {0.179872f, 0.966623f, 1.21304f}, {3.24348f, 2.5983f, 2.3493f}},
      {"Hg", {1.98525f, 1.52277f, 0.999883f}, {5.24457f, 4.61594f, 3.76274f}},
      {"HgTe", {3.96465f, 3.40991f, 2.92525f}, {1.3607f, 1.6631f, 1.90256f}},
      {"HgTe_palik", {3.96465f, 3.40991f, 2.92525f}, {1.3607f, 1.6631f, 1.90256f}},
      {"Hg_palik", {1.98525f, 1.52277f, 0.999883f}, {5.24457f, 4.61594f, 3.76274f}},
      {"Ir", {2.55882f, 2.19829f, 1.77902f}, {4.63717f, 4.29241f, 3.593f}},
      {"Ir_palik", {2.55882f, 2.19829f, 1.77902f}, {4.63717f, 4.29241f, 3.593f}},
      {"K", {0.0531731f, 0.0489515f, 0.0419916f}, {1.74256f, 1.42533f, 1.00411f}},
      {"K_palik", {0.0531731f, 0.0489515f, 0.0419916f}, {1.74256f, 1.42533f, 1.00411f}},
      {"Li", {0.22034f, 0.206439f, 0.242923f}, {2.93268f, 2.44153f, 1.83466f}},
      {"Li_palik", {0.22034f, 0.206439f, 0.242923f}, {2.93268f, 2.44153f, 1.83466f}},
      {"MgO", {1.73438f, 1.74079f, 1.75403f}, {-9.05209e-12f, 3.4443e-12f, 2.04336e-11f}},
      {"MgO_palik", {1.73438f, 1.74079f, 1.75403f}, {-9.05209e-12f, 3.4443e-12f, 2.04336e-11f}},
      {"Mo", {3.71936f, 3.71936f, 3.05295f}, {3.41105f, 3.60787f, 3.46529f}},
      {"Mo_palik", {3.71936f, 3.71936f, 3.05295f}, {3.41105f, 3.60787f, 3.46529f}},
      {"Na_palik", {0.0500846f, 0.0591459f, 0.0681855f}, {2.63369f, 2.23136f, 1.73634f}},
      {"Nb", {2.84096f, 2.9414f, 2.6348f}, {2.85543f, 2.88729f, 2.83749f}},
      {"Nb_palik", {2.84096f, 2.9414f, 2.6348f}, {2.85543f, 2.88729f, 2.83749f}},
      {"Ni_palik", {1.96178f, 1.75612f, 1.61323f}, {3.72814f, 3.22096f, 2.57904f}},
      {"Rh", {2.14356f, 1.96342f, 1.70949f}, {5.6214f, 4.96518f, 4.37224f}},
      {"Rh_palik", {2.14356f, 1.96342f, 1.70949f}, {5.6214f, 4.96518f, 4.37224f}},
      {"Se", {3.39292f, 2.99573f, 3.10164f}, {0.631554f, 0.670994f, 0.573625f}},
      {"Se-e", {4.78663f, 4.38753f, 4.48875f}, {0.732373f, 1.16006f, 1.72116f}},
      {"Se-e_palik", {4.78663f, 4.38753f, 4.48875f}, {0.732373f, 1.16006f, 1.72116f}},
      {"Se_palik", {3.39292f, 2.99573f, 3.10164f}, {0.631554f, 0.670994f, 0.573625f}},
      {"SiC", {2.63316f, 2.66365f, 2.72679f}, {-5.06543e-07f, -1.3637e-07f, 1.09431e-05f}},
      {"SiC_palik", {2.63316f, 2.66365f, 2.72679f}, {-5.06543e-07f, -1.3637e-07f, 1.09431e-05f}},
      {"SnTe", {3.74699f, 2.0977f, 1.40826f}, {0.0f, 0.0f, 0.0f}},
      {"SnTe_palik", {3.74699f, 2.0977f, 1.40826f}, {0.0f, 0.0f, 0.0f}},
      {"Ta", {1.71938f, 2.51796f, 2.89113f}, {1.99199f, 1.83971f, 2.14104f}},
      {"Ta_palik", {1.71938f, 2.51796f, 2.89113f}, {1.99199f, 1.83971f, 2.14104f}},
      {"Te", {6.12679f, 4.73471f, 2.89924f}, {2.71609f, 3.71127f, 3.6218f}},
      {"Te-e", {6.21576f, 4.54495f, 2.60464f}, {4.64616f, 5.21147f, 4.39716f}},
      {"Te-e_palik", {6.21576f, 4.54495f, 2.60464f}, {4.64616f, 5.21147f, 4.39716f}},
      {"Te_palik", {6.12679f, 4.73471f, 2.89924f}, {2.71609f, 3.71127f, 3.6218f}},
      {"ThF4", {1.51943f, 1.52095f, 1.52612f}, {0.0f, 0.0f, 0.0f}},
      {"ThF4_palik", {1.51943f, 1.52095f, 1.52612f}, {0.0f, 0.0f, 0.0f}},
      {"TiC", {3.06934f, 2.99352f, 2.83992f}, {2.70837f, 2.48146f, 2.38938f}},
      {"TiC_palik", {3.06934f, 2.99352f, 2.83992f}, {2.70837f, 2.48146f, 2.38938f}},
      {"TiN", {1.36652f, 1.21418f, 1.5172f}, {2.78847f, 2.05521f, 1.21134f}},
      {"TiN_palik", {1.36652f, 1.21418f, 1.5172f}, {2.78847f, 2.05521f, 1.21134f}},
      {"TiO2", {2.86958f, 2.95399f, 3.19505f}, {6.70728e-05f, -7.83143e-05f, 0.000699603f}},
      {"TiO2-e", {2.57911f, 2.64974f, 2.84007f}, {9.39032e-06f, -1.72662e-05f, 0.000194045f}},
      {"TiO2-e_palik", {2.57911f, 2.64974f, 2.84007f}, {9.39032e-06f, -1.72662e-05f, 0.000194045f}},
      {"TiO2_palik", {2.86958f, 2.95399f, 3.19505f}, {6.70728e-05f, -7.83143e-05f, 0.000699603f}},
      {"VC", {3.03398f, 2.90416f, 2.7853f}, {2.54452f, 2.3203f, 2.15887f}},
      {"VC_palik", {3.03398f, 2.90416f, 2.7853f}, {2.54452f, 2.3203f, 2.15887f}},
      {"VN", {2.37649f, 2.23614f, 2.13352f}, {2.51365f, 2.17083f, 1.7773f}},
      {"VN_palik", {2.37649f, 2.23614f, 2.13352f}, {2.51365f, 2.17083f, 1.7773f}},
      {"V_palik", {3.55117f, 3.70452f, 3.03694f}, {2.89719f, 3.04664f, 3.42236f}},
      {"W", {3.62455f, 3.48243f, 3.29722f}, {2.90435f, 2.74823f, 2.49994f}},
      {"a-C", {2.44313f, 2.34924f, 2.16451f}, {0.737354f, 0.842291f, 0.896733f}},
      {"d-C", {2.41214f, 2.42349f, 2.44975f}, {0.0f, 0.0f, 0.0f}},
      {"d-C_palik", {2.41214f, 2.42349f, 2.44975f}, {0.0f, 0.0f, 0.0f}},
};

}  // namespace

Vec3 cie1931_xyz(float nm) { return cie_xyz_d(double(nm)).cast<float>(); }

Rgb xyz_to_linear_rgb(const Vec3& xyz) { return xyz_to_rgb_d(xyz.cast<double>()).cast<float>().array(); }

Rgb srgb_to_linear(const Rgb& c) {
  Rgb out;
  for (int i = 0; i < 3; ++i) {
    const float v = c[i];
    out[i] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  return out;
}

Rgb spectrum_to_rgb(const std::vector<std::pair<float, float>>& samples) {
  if (samples.empty()) return Rgb::Zero();
  auto eval = [&](double nm) -> double {
    if (nm <= double(samples.front().first)) return double(samples.front().second);
    if (nm >= double(samples.back().first)) return double(samples.back().second);
    size_t i = 1;
    while (double(samples[i].first) < nm) ++i;
    const double l0 = samples[i - 1].first, v0 = samples[i - 1].second;
    const double l1 = samples[i].first, v1 = samples[i].second;
    const double t = (nm - l0) / (l1 - l0);
    return (1.0 - t) * v0 + t * v1;
  };
  const Vec3d rgb = xyz_to_rgb_d(integrate_xyz(eval));
  return rgb.cwiseQuotient(flat_rgb()).cast<float>().array();
}

std::optional<float> named_ior(const std::string& name) {
  // Mitsuba's documented table of dielectric indices (its manual, "Dielectric" plugin).
  static const std::array<std::pair<const char*, float>, 23> kTable = {{
      {"vacuum", 1.0f},           {"helium", 1.000036f},    {"hydrogen", 1.000132f},
      {"air", 1.000277f},         {"carbon dioxide", 1.00045f}, {"water", 1.3330f},
      {"acetone", 1.36f},         {"ethanol", 1.361f},      {"carbon tetrachloride", 1.461f},
      {"glycerol", 1.4729f},      {"benzene", 1.501f},      {"silicone oil", 1.52045f},
      {"bromine", 1.661f},        {"water ice", 1.31f},     {"fused quartz", 1.458f},
      {"pyrex", 1.470f},          {"acrylic glass", 1.49f}, {"polypropylene", 1.49f},
      {"bk7", 1.5046f},           {"sodium chloride", 1.544f}, {"amber", 1.55f},
      {"pet", 1.5750f},           {"diamond", 2.419f},
  }};
  for (const auto& [n, v] : kTable)
    if (name == n) return v;
  return std::nullopt;
}

std::optional<ConductorIor> named_conductor(const std::string& name) {
  if (name == "none") return ConductorIor{Rgb::Zero(), Rgb::Zero()};
  for (const ConductorTableEntry& e : kConductors)
    if (name == e.name)  // tiny negative k of dielectric entries are fit noise: clamp
      return ConductorIor{Rgb(e.eta[0], e.eta[1], e.eta[2]), Rgb(e.k[0], e.k[1], e.k[2]).max(0.0f)};
  return std::nullopt;
}

std::string conductor_names() {
  std::string out = "none";
  for (const ConductorTableEntry& e : kConductors) out += std::string(", ") + e.name;
  return out;
}

}  // namespace dp::scene
