#pragma once
// Colour science for tests, written from the published formulas (not from
// the code under test):
// - CIEDE2000: G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference
//   formula: implementation notes, supplementary test data, and mathematical
//   observations", Color Res. Appl. 30(1), 2005 (kL = kC = kH = 1);
// - sRGB (IEC 61966-2-1) to CIELAB, D65 white;
// - colour vision deficiency: Machado, Oliveira, Fernandes, "A
//   physiologically-based model for simulation of color vision deficiency",
//   IEEE TVCG 15(6), 2009, the severity 1.0 matrices on linear RGB.

#include <array>

#include "hqview/image/color.h"

namespace hq::test {

struct Lab {
  double l, a, b;
};

// CIEDE2000 colour difference of two CIELAB colours.
double ciede2000(const Lab& x, const Lab& y);

// CIELAB (D65) of linear RGB in [0, 1] / of an sRGB colour.
Lab lab_of_linear(const std::array<double, 3>& rgb);
Lab lab_of(const Rgba8& c);
// Linear RGB of an sRGB colour.
std::array<double, 3> linear_of(const Rgba8& c);

using CvdMatrix = std::array<std::array<double, 3>, 3>;
// Machado et al. 2009, severity 1.0.
inline constexpr CvdMatrix kProtanopia{
    {{0.152286, 1.052583, -0.204868}, {0.114503, 0.786281, 0.099216}, {-0.003882, -0.048116, 1.051998}}};
inline constexpr CvdMatrix kDeuteranopia{
    {{0.367322, 0.860646, -0.227968}, {0.280085, 0.672501, 0.047413}, {-0.011820, 0.042940, 0.968881}}};
inline constexpr CvdMatrix kTritanopia{
    {{1.255528, -0.076749, -0.178779}, {-0.078411, 0.930809, 0.147602}, {0.004733, 0.691367, 0.303900}}};

// CIELAB of the colour as seen with the deficiency (linear RGB times m,
// clamped to [0, 1]).
Lab simulated(const Rgba8& c, const CvdMatrix& m);

// CIEDE2000 of two sRGB colours; the smallest over the three simulations.
double delta_e(const Rgba8& a, const Rgba8& b);
double worst_cvd_delta_e(const Rgba8& a, const Rgba8& b);

}  // namespace hq::test
