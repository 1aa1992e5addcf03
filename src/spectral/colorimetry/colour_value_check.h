// The checks on colour values a user gives directly (an XYZ, a CIELAB, a linear RGB, a reference white), shared
// by the tools and the Python module so each refuses the same values with the same explanation; the caller says
// where the value came from (an option, or a Python argument and index).
#pragma once

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/error.h"

namespace rimu {

/// The largest magnitude of a colour component anything accepts. Within ±1e30 every conversion (matrices, CIELAB's
/// cube roots against a white of at least 1e-30, CIEDE2000's seventh powers, an upsampled spectrum) stays a finite
/// double, so no result is ever NaN or Inf.
inline constexpr double kMaxColourComponent = 1e30;

/// One component of a colour (a channel of an image): finite and within ±kMaxColourComponent. Throws at `where`.
void check_colour_component(double value, const SourceLocation& where);

/// Three components of a colour: finite and within ±kMaxColourComponent. Throws InputError at `where`.
void check_colour_components(double a, double b, double c, const SourceLocation& where);

/// A reference white (CIELAB's, chromatic adaptation's): X, Y, Z each in [1/kMaxColourComponent,
/// kMaxColourComponent]. A zero or negative white has no CIELAB (X/Xn divides by it). Throws InputError at `where`.
void check_white_xyz(const Xyz& white, const SourceLocation& where);

/// An XYZ whose chromaticity xy is defined: valid components and X + Y + Z > 0 (black, or a sum that is not
/// positive, has none: chromaticity_of would return (0, 0) or a point outside the diagram). Throws at `where`.
void check_has_chromaticity(const Xyz& xyz, const SourceLocation& where);
/// The same for the CIE 1960 and 1976 UCS (u, v), (u', v'): also X + 15Y + 3Z > 0 (their denominator).
void check_has_ucs_chromaticity(const Xyz& xyz, const SourceLocation& where);

}  // namespace rimu
