#include "render/scene/spectrum_input.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <sstream>
#include <utility>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/photometry/light_units.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/spectra/spectral_value_range.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "render/scene/rgb_transport_inputs.h"

namespace rimu {
namespace {

void check_range(const JsonCursor& where, const Spectrum& s, SpectrumRole role) {
  // Checked at the integer wavelengths of 360-830 nm: tabulated inputs are linear between their knots, and
  // every analytic one here is smooth, so this finds any negative lobe a user could have written.
  for (int nm = 360; nm <= 830; ++nm) {
    const double v = s.value(nm);
    if (!std::isfinite(v)) where.fail("the spectrum is not finite at " + std::to_string(nm) + " nm");
    if (role == SpectrumRole::ior && !(v > 0.0))
      where.fail("an index of refraction must be positive; it is " + std::to_string(v) + " at " + std::to_string(nm) + " nm");
    if (role != SpectrumRole::ior && v < 0.0)
      where.fail("the spectrum is negative (" + std::to_string(v) + ") at " + std::to_string(nm) + " nm");
    // Every input number is at most 1e30, but a product (an RGB or a table times "scale") need not be: beyond 1e30
    // the light's single-precision radiance overflows and every sample of it is discarded (a black render).
    if (role == SpectrumRole::emission && v > kMaxLightAmount) {
      char text[64];
      std::snprintf(text, sizeof text, "%g at %d nm", v, nm);
      where.fail("the emission is " + std::string(text) + "; at most 1e30 (beyond, its single-precision radiance "
                 "overflows): lower \"scale\"");
    }
    // Materials would clamp a reflectance above 1 (it would create energy); say so instead of changing the input.
    // The 1e-6 allows a product such as 0.5 × 2 rounded in float.
    if (role == SpectrumRole::reflectance && v > 1.0 + 1e-6)
      where.fail("a reflectance cannot exceed 1; it is " + std::to_string(v) + " at " + std::to_string(nm) + " nm");
  }
}

}  // namespace

// Its basis (built on first use) costs ~20 ms, seconds under the fuzz targets' sanitizers, where every input is a
// new scene of the same library; it holds no reference to the library, and is const and safe to share between
// threads.
std::shared_ptr<const RgbUpsampler> shared_upsampler(SpectralLibrary& library, const std::string& space_name) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, std::string>, std::shared_ptr<const RgbUpsampler>> upsamplers;
  const std::lock_guard lock(mutex);
  auto& upsampler = upsamplers[{library.root().string(), space_name}];
  if (!upsampler) upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named(space_name));
  return upsampler;
}

std::string ScaledSpectrum::describe() const {
  std::ostringstream out;
  out << scale_ << " × " << base_->describe();
  return out.str();
}

double SpectrumInputContext::emission_rgb_scale() {
  if (emission_rgb_scale_ == 0.0) {
    const Observer& o = library_.observer(StandardObserver::cie1931_2deg);
    emission_rgb_scale_ =
        kMaxLuminousEfficacy_lm_W * integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return o.y_bar.value(l); });
  }
  return emission_rgb_scale_;
}

std::shared_ptr<const RgbUpsampler> SpectrumInputContext::upsampler(const std::string& space_name,
                                                                   const JsonCursor& where) {
  auto it = upsamplers_.find(space_name);
  if (it != upsamplers_.end()) return it->second;
  try {
    return upsamplers_.emplace(space_name, shared_upsampler(library_, space_name)).first->second;
  } catch (const InputError& e) {
    where.fail(e.explanation());
  }
}

SpectrumPtr SpectrumInputContext::transport_form(SpectrumPtr spectrum, SpectrumRole role) {
  return rgb_transport_ ? rgb_transport_form(spectrum, role, library_) : spectrum;
}

SpectrumPtr SpectrumInputContext::parse_spectral(const JsonCursor& value, SpectrumRole role) {
  const bool was_converting = converting_;
  converting_ = false;
  try {
    SpectrumPtr s = parse(value, role);
    converting_ = was_converting;
    return s;
  } catch (...) {
    converting_ = was_converting;
    throw;
  }
}

SpectrumPtr SpectrumInputContext::parse(const JsonCursor& value, SpectrumRole role) {
  // Rgb transport: the result is converted at the end unless an RGB was given (used as is) or a named spectrum
  // was parsed (already converted by the recursive call).
  const bool convert = rgb_transport_ && converting_;
  std::optional<Rgb> given_rgb;
  bool converted = false;
  if (value.is_number()) {
    const double c = value.number(role == SpectrumRole::ior ? 1e-6 : 0.0, role == SpectrumRole::reflectance ? 1.0 : 1e30);
    const SpectrumPtr constant = std::make_shared<ConstantSpectrum>(c);
    return convert ? rgb_transport_form(constant, role, library_) : constant;
  }
  if (!value.is_object())
    value.fail("expected a spectrum: a number, or an object with one of constant, illuminant, csv, wavelengths_nm, "
               "blackbody, daylight, rgb, spectrum");
  SpectrumPtr base;
  if (value.has("constant")) {
    value.only_keys({"constant", "scale"});
    base = std::make_shared<ConstantSpectrum>(value.at("constant").number(0.0, 1e30));
  } else if (value.has("illuminant")) {
    value.only_keys({"illuminant", "scale"});
    const std::string name = value.at("illuminant").string();
    base = value.at("illuminant").blame([&] { return library_.illuminant(name); });
  } else if (value.has("csv")) {
    value.only_keys({"csv", "column", "scale"});
    const std::filesystem::path path = scene_directory_ / value.at("csv").string();
    const std::string column = value.string_or("column", "");
    // Light outside a measured emission table is absent; a reflectance, index or coefficient keeps its end value.
    const Extrapolation extrapolation = role == SpectrumRole::emission ? Extrapolation::zero : Extrapolation::clamp;
    base = value.at("csv").blame([&] {
      const CsvTable table = CsvTable::read(path);
      if (table.column_count() < 2) throw InputError({path.string(), 1, ""}, "expected wavelength_nm and a value column");
      const std::string c = column.empty() ? table.header()[1] : column;
      return std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(table, c, extrapolation));
    });
  } else if (value.has("wavelengths_nm")) {
    // An inline table: the same piecewise-linear function and end rule as a CSV column.
    value.only_keys({"wavelengths_nm", "values", "scale"});
    const auto list = [](const JsonCursor& c) {
      if (!c.is_array() || c.size() < 2) c.fail("expected an array of at least two numbers");
      std::vector<double> out;
      for (size_t i = 0; i < c.size(); ++i) out.push_back(c.at(i).number());
      return out;
    };
    std::vector<double> lambda_nm = list(value.at("wavelengths_nm")), values = list(value.at("values"));
    for (size_t i = 0; i < values.size(); ++i)
      if (const std::string why = spectral_value_range_error(values[i]); !why.empty()) value.at("values").at(i).fail(why);
    if (lambda_nm.size() != values.size())
      value.at("values").fail("expected " + std::to_string(lambda_nm.size()) + " values, one per wavelength, not " +
                              std::to_string(values.size()));
    const Extrapolation extrapolation = role == SpectrumRole::emission ? Extrapolation::zero : Extrapolation::clamp;
    base = value.at("wavelengths_nm").blame([&] {
      return std::make_shared<TabulatedSpectrum>(std::move(lambda_nm), std::move(values), extrapolation, "");
    });
  } else if (value.has("blackbody")) {
    value.only_keys({"blackbody", "scale"});
    const double t = value.at("blackbody").number(1.0, 1e6);
    base = std::make_shared<BlackbodySpectrum>(t, BlackbodySpectrum::Scale::peak_one);
  } else if (value.has("daylight")) {
    value.only_keys({"daylight", "scale"});
    const double cct = value.at("daylight").number(4000.0, 25000.0);
    base = std::make_shared<TabulatedSpectrum>(daylight_spectrum(library_.daylight_basis(), cct));
  } else if (value.has("rgb")) {
    value.only_keys({"rgb", "space", "scale"});
    if (role == SpectrumRole::ior) value.at("rgb").fail("an index of refraction cannot be given as RGB");
    if (role == SpectrumRole::coefficient)
      value.at("rgb").fail("give coefficients as spectra; use albedo + mean_free_path for colours");
    const Vec3 rgb = value.at("rgb").vec3();
    const std::string space = value.string_or("space", "srgb-linear");
    const RgbUpsampler& up = *upsampler(space, value.has("space") ? value.at("space") : value);
    const Rgb colour{rgb.x, rgb.y, rgb.z};
    if (convert) given_rgb = to_linear_srgb(colour, RgbColourSpace::named(space));
    if (role == SpectrumRole::reflectance) {
      base = std::make_shared<ReflectanceSpectrum>(up.upsample_reflectance(colour, value.where()).spectrum);
    } else {
      base = std::make_shared<ScaledSpectrum>(
          std::make_shared<EmissionSpectrum>(up.upsample_emission(colour, value.where()).spectrum), emission_rgb_scale());
    }
  } else if (value.has("spectrum")) {
    value.only_keys({"spectrum", "scale"});
    const std::string name = value.at("spectrum").string();
    if (!named_ || !named_->has(name))
      value.at("spectrum").fail("no spectrum named '" + name + "' in the scene's \"spectra\" section");
    const auto repeat = std::find(named_chain_.begin(), named_chain_.end(), name);
    if (repeat != named_chain_.end()) {
      std::string cycle;
      for (auto it = repeat; it != named_chain_.end(); ++it) cycle += "'" + *it + "' → ";
      value.at("spectrum").fail("named spectra refer to each other in a cycle: " + cycle + "'" + name + "'");
    }
    if (named_chain_.size() >= kMaxNamedSpectrumDepth)
      value.at("spectrum").fail("named spectra refer to each other more than " +
                                std::to_string(kMaxNamedSpectrumDepth) + " deep (from '" + named_chain_.front() +
                                "'); give one of them its value directly");
    named_chain_.push_back(name);
    // Popped on every way out, so an error caught above (a test, a tool trying the next form) leaves no stale name.
    struct Pop {
      std::vector<std::string>& chain;
      ~Pop() { chain.pop_back(); }
    } pop{named_chain_};
    base = parse(named_->at(name), role);
    converted = convert;
  } else {
    value.fail("expected one of the keys constant, illuminant, csv, wavelengths_nm, blackbody, daylight, rgb, spectrum");
  }
  if (value.has("scale")) {
    const double scale = value.at("scale").number(0.0, 1e30);
    base = std::make_shared<ScaledSpectrum>(std::move(base), scale);
    if (given_rgb) given_rgb = Rgb{given_rgb->r * scale, given_rgb->g * scale, given_rgb->b * scale};
  }
  check_range(value, *base, role);
  if (convert && !converted) base = rgb_transport_form(base, role, library_, given_rgb ? &*given_rgb : nullptr);
  return base;
}

}  // namespace rimu
