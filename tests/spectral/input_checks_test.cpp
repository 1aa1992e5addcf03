// The checks every front end shares (tools, scenes, the Python module): each names the place the caller gives it.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "spectral/library/colorimetry_options.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/spectra/spectrum_values_check.h"

using namespace rimu;

namespace {

// The message of the InputError `f` throws ("" if none).
template <typename F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

SourceLocation at_index(std::size_t i) { return {"", 0, "values[" + std::to_string(i) + "]"}; }

}  // namespace

TEST_CASE("spectrum values are checked at the sample the caller names") {
  CHECK(message_of([] { check_spectral_power({1, 2, -0.5}, at_index); }) ==
        "values[2]: spectral power cannot be negative, found -0.5");
  CHECK(message_of([] { check_spectral_power({1, NAN}, at_index); }) == "values[1]: spectral power nan is not a finite number");
  CHECK(message_of([] { check_reflectance_factors({0.2, 45}, at_index); }) ==
        "values[1]: reflectance factor 45 is above 1.5: expected a factor in 0-1 (in percent?)");
  CHECK(message_of([] { check_reflectance_factors({-0.5, 0.2}, at_index); }) ==
        "values[0]: reflectance factor -0.5 is negative: expected a factor in 0-1");
  CHECK(message_of([] { check_reflectance_factors({0.0, 1.3}, at_index); }).empty());  // fluorescent: accepted
  CHECK(message_of([] { check_wavelengths_nm({0.38, 0.58, 0.78}, at_index); }).find("values[2]: the wavelengths end at "
                                                                                    "0.78, below 100 nm: are they in "
                                                                                    "micrometres?") == 0);
  CHECK(message_of([] { check_wavelengths_nm({400, 400}, at_index); }).find("values[1]: wavelengths must increase") == 0);
  CHECK(message_of([] { check_wavelengths_nm({50, 380}, at_index); }).empty());
}

TEST_CASE("colour values: finite within 1e30, whites positive, chromaticity only where X+Y+Z > 0") {
  const SourceLocation white{"", 0, "white"};
  CHECK(message_of([&] { check_white_xyz({0, 0, 0}, white); }).find("white: a reference white needs") == 0);
  CHECK(message_of([&] { check_white_xyz({95.047, 100, 108.883}, white); }).empty());
  CHECK(message_of([&] { check_colour_components(1e308, 0, 0, white); }).find("white: expected three finite") == 0);
  CHECK(message_of([&] { check_colour_components(-1e30, 0, 1e30, white); }).empty());
  CHECK(message_of([&] { check_has_chromaticity({0, 0, 0}, white); }).find("is not positive") != std::string::npos);
  CHECK(message_of([&] { check_colour_component(INFINITY, white); }).find("white: expected a finite number") == 0);
}

TEST_CASE("observer and method options read the same for every front end") {
  CHECK(standard_observer_option(10, {}) == StandardObserver::cie1964_10deg);
  CHECK(message_of([] { standard_observer_option(4, {"", 0, "observer"}); }).find("observer: expected 2 or 10") == 0);
  CHECK(!tristimulus_method_option("auto", {}).has_value());
  CHECK(tristimulus_method_option("1nm", {}) == TristimulusMethod::interpolate_1nm);
  CHECK(message_of([] { tristimulus_method_option("x", {"", 0, "method"}); }) ==
        "method: unknown tristimulus method 'x'; use auto, native, 1nm or astm-e308");
}
