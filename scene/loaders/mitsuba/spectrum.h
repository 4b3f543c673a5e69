// Spectral data -> linear Rec. 709 RGB for the Mitsuba importer, and the named
// refractive indices Mitsuba accepts in place of numbers.
//
// Conversion: a spectrum given as wavelength:value pairs (nm) is the piecewise-linear
// function through the pairs, held constant beyond the first/last sample. It is
// integrated against the CIE 1931 2-degree colour matching functions (analytic fit of
// Wyman, Sloan and Shirley 2013, see spectrum.cpp) over 360..830 nm, converted
// XYZ -> linear Rec. 709 (sRGB primaries, D65 white), and each channel is divided by
// the RGB of the flat spectrum 1 (white balance to the equal-energy illuminant E), so
// a constant spectrum c maps to the grey (c, c, c) — exactly what Mitsuba's constant
// <spectrum value="c"/> means in its RGB mode.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"

namespace dp::scene {

// CIE 1931 x̄ ȳ z̄ at wavelength `nm` (analytic multi-lobe Gaussian fit).
Vec3 cie1931_xyz(float nm);
// XYZ (D65 white) -> linear Rec. 709 RGB.
Rgb xyz_to_linear_rgb(const Vec3& xyz);
// sRGB transfer curve (IEC 61966-2-1) decoded to linear, per channel.
Rgb srgb_to_linear(const Rgb& c);
// Samples (wavelength nm, value), wavelengths strictly increasing (checked by callers).
Rgb spectrum_to_rgb(const std::vector<std::pair<float, float>>& samples);

// Index of refraction of a named dielectric (Mitsuba's table: "vacuum", "air", "water",
// "bk7", "diamond", ...). nullopt if unknown.
std::optional<float> named_ior(const std::string& name);

struct ConductorIor {
  Rgb eta, k;
};
// RGB complex index of refraction of a named conductor ("Cu", "Au", "Ag", "Al", "Cr",
// ...; "none" = a perfect mirror, eta 0, k 0). nullopt if unknown.
std::optional<ConductorIor> named_conductor(const std::string& name);
// Comma-separated list of the known conductor names (for error messages).
std::string conductor_names();

}  // namespace dp::scene
