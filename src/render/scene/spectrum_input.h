// Spectral inputs of a scene: every key that takes a spectrum accepts the same forms.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/scene/json_cursor.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// How a spectrum is used decides how RGB is upsampled and what values are allowed.
enum class SpectrumRole {
  reflectance,  ///< [0, 1]: RGB is upsampled with gamut mapping (RgbUpsampler::upsample_reflectance)
  emission,     ///< ≥ 0, unbounded: RGB is upsampled as the colour space's white shaped (upsample_emission)
  ior,          ///< > 0: index of refraction; RGB is not accepted
  coefficient,  ///< ≥ 0, unbounded, per metre (a medium's σ_a, σ_s): RGB is not accepted (a coefficient is not a
                ///< colour); tables are clamped beyond their ends
};

/// The upsampler of colour space `space_name` for data library `library`: one per (library folder, colour space)
/// for the whole process, built on first use, so every scene and pbrt import of a process shares it. Throws
/// InputError for an unknown colour space (RgbColourSpace::named).
std::shared_ptr<const RgbUpsampler> shared_upsampler(SpectralLibrary& library, const std::string& space_name);

/// Shared state while a scene loads: the data library, the scene's folder (CSV paths are relative to it),
/// named spectra from the scene's "spectra" section, and one upsampler per colour space (built on first use).
class SpectrumInputContext {
 public:
  SpectrumInputContext(SpectralLibrary& library, std::filesystem::path scene_directory)
      : library_(library), scene_directory_(std::move(scene_directory)) {}

  /// Parses a spectral value. Accepted forms (all objects may add "scale": k):
  ///   0.5                                   a constant
  ///   {"constant": 0.5}
  ///   {"illuminant": "D65"}                 a CIE illuminant by name (relative power, 100 at 560 nm)
  ///   {"csv": "file.csv", "column": "red"}  a table, path relative to the scene file
  ///   {"blackbody": 2700}                   Planck at T kelvin, scaled so its peak is 1
  ///   {"daylight": 6500}                    CIE daylight at a CCT (4000-25000 K), ≈100 at 560 nm
  ///   {"rgb": [r, g, b], "space": "srgb-linear"}   upsampled (see SpectrumRole)
  ///   {"spectrum": "name"}                  a spectrum defined in the scene's "spectra" section
  /// Errors name the key path.
  SpectrumPtr parse(const JsonCursor& value, SpectrumRole role);
  /// parse() without the rgb-transport conversion: for inputs that rgb transport point-samples (a conductor's n, k).
  SpectrumPtr parse_spectral(const JsonCursor& value, SpectrumRole role);

  /// Rgb transport (WavelengthMode::rgb): from now on parse() returns every input in its RGB form
  /// (render/scene/rgb_transport_inputs.h). Set by the loader from the scene's "integrator" section, before materials.
  void set_rgb_transport(bool on) { rgb_transport_ = on; }
  bool rgb_transport() const { return rgb_transport_; }
  /// `spectrum` as the current mode carries it: unchanged, or its rgb-transport form (for spectra built outside
  /// parse(), e.g. a named glass).
  SpectrumPtr transport_form(SpectrumPtr spectrum, SpectrumRole role);

  /// A named spectrum may refer to another, and so on, at most this deep (each level is a recursive parse).
  static constexpr size_t kMaxNamedSpectrumDepth = 64;

  /// Registers the scene's "spectra" section (an object of name → spectral value, parsed lazily by role).
  /// References between them are resolved when parsed; a cycle is an error that names it.
  void set_named(const JsonCursor& section) { named_.emplace(section); }

  SpectralLibrary& library() { return library_; }
  /// RGB emission in a scene is in film units: an RGB whose luminance is Y renders with film Y (render/film/film.h, where
  /// an equal-energy radiance of 1 W/(m²·sr·nm) gives Y = 1). The upsampler reads Y as cd/m², so RGB emission is
  /// multiplied by this factor, K_m·∫ȳ dλ ≈ 72 983 cd/m² per film unit (CIE 1931 2°, 360-830 nm at 1 nm).
  double emission_rgb_scale();
  const std::filesystem::path& scene_directory() const { return scene_directory_; }
  /// The upsampler of a colour space, built on first use and shared (textures keep it after loading).
  std::shared_ptr<const RgbUpsampler> upsampler(const std::string& space_name, const JsonCursor& where);

 private:
  SpectralLibrary& library_;
  std::filesystem::path scene_directory_;
  std::optional<JsonCursor> named_;
  std::map<std::string, std::shared_ptr<const RgbUpsampler>> upsamplers_;
  std::vector<std::string> named_chain_;  // the named spectra being parsed, outermost first
  double emission_rgb_scale_ = 0.0;
  bool rgb_transport_ = false;
  bool converting_ = true;  // false inside parse_spectral()
};

/// A spectrum multiplied by a constant.
class ScaledSpectrum final : public Spectrum {
 public:
  ScaledSpectrum(SpectrumPtr base, double scale) : base_(std::move(base)), scale_(scale) {}
  double value(double lambda_nm) const override { return scale_ * base_->value(lambda_nm); }
  SampledSpectrum sample(const SampledWavelengths& lambda) const override {
    return base_->sample(lambda) * Float4(float(scale_));
  }
  double max_value() const override { return scale_ * base_->max_value(); }
  std::string describe() const override;

 private:
  SpectrumPtr base_;
  double scale_;
};

}  // namespace rimu
