// A measured BRDF in the form of Dupuy & Jakob 2018 ("An Adaptive Parameterization for Efficient Material
// Acquisition and Rendering", SIGGRAPH Asia): the tables of one file of the RGL material database, which pbrt-v4's
// `measured` material reads. MeasuredBsdf evaluates and samples it.
//
// The model. The BRDF is written as a microfacet-like product,
//     f(ωo, ωi) = S(u; ωo, λ) · D(ωm) / (4 σ(ωo) cos θi),   ωm = (ωo + ωi)/|ωo + ωi|,
// with D the material's retro-reflection-derived normal distribution (`ndf`), σ(ωo) = ∫ D(ωm) ⟨ωo, ωm⟩ dωm its
// projected area (`sigma`), and S the measured spectral factor (`spectra`: Fresnel, shadowing, everything else),
// tabulated not over directions but over the unit square u that the visible-normal warp (`vndf`: the density of
// D(ωm)⟨ωo, ωm⟩/σ(ωo) in ωm) maps to ωm. Tabulating there puts the measurements where the lobe is. Sampling composes
// two warps: `luminance` (S's luminance over u, per ωo) and then `vndf`.
//
// Angles map to the unit square as in the paper: u_θ = √(2θ/π), u_φ = φ/(2π) + ½ (φ from −π to π); the tables'
// incident-direction parameters are φi, θi in radians. An isotropic file (two φ entries or fewer) tabulates ωm's φ
// relative to ωo's.
#pragma once

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "transport/bsdfs/tensor_file.h"
#include "transport/sampling/bilinear_warp_2d.h"

namespace rimu {

class MeasuredBrdf {
 public:
  /// The tables of an RGL tensor file. Throws InputError naming the file and field: a missing field, a type or
  /// shape other than the format's, extents below 2, incident angles or wavelengths that do not increase, values
  /// that are not finite (or negative where a density is meant), an anisotropic file that does not span 2π in φ.
  static MeasuredBrdf from_tensor_file(const TensorFile& file);
  /// Reads and checks a file (TensorFile::read, then from_tensor_file).
  static MeasuredBrdf read(const std::filesystem::path& path);

  bool isotropic() const { return isotropic_; }
  /// Whether the normal distribution peaks above a GGX lobe of TrowbridgeReitz::kGlossyAlpha (D > 1/(π α²)): a lobe
  /// that narrow gets the glossy treatment of next-event estimation (BsdfFlags::has_glossy).
  bool glossy() const { return glossy_; }
  const std::string& name() const { return name_; }
  /// Wavelengths (nm) the spectra were measured at; outside them the nearest one's values hold.
  const std::vector<float>& wavelengths_nm() const { return wavelengths_nm_; }
  size_t memory_bytes() const;

  // The tables (see the header comment). Parameters: (φi, θi) for vndf and luminance, (φi, θi, λ) for spectra.
  const BilinearWarp2D& ndf() const { return ndf_; }
  const BilinearWarp2D& sigma() const { return sigma_; }
  const BilinearWarp2D& vndf() const { return vndf_; }
  const BilinearWarp2D& luminance() const { return luminance_; }
  const BilinearWarp2D& spectra() const { return spectra_; }

  /// θ ↔ u_θ and φ ↔ u_φ of the paper's parameterisation.
  static float theta_to_u(float theta) { return std::sqrt(theta * (2.0f / kPi)); }
  static float phi_to_u(float phi) { return phi * (0.5f / kPi) + 0.5f; }
  static float u_to_theta(float u) { return u * u * (kPi / 2.0f); }
  static float u_to_phi(float u) { return (2.0f * u - 1.0f) * kPi; }

 private:
  static constexpr float kPi = std::numbers::pi_v<float>;

  std::string name_;
  bool isotropic_ = true;
  bool glossy_ = false;
  std::vector<float> wavelengths_nm_;
  BilinearWarp2D ndf_, sigma_, vndf_, luminance_, spectra_;
};

using MeasuredBrdfPtr = std::shared_ptr<const MeasuredBrdf>;

}  // namespace rimu
