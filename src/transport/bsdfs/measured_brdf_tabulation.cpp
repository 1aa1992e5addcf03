#include "transport/bsdfs/measured_brdf_tabulation.h"

#include <cassert>
#include <cmath>
#include <numbers>

#include "transport/bsdfs/fresnel.h"
#include "transport/bsdfs/measured_brdf.h"
#include "transport/sampling/bilinear_warp_2d.h"

namespace rimu {

namespace {

Vec3 direction(float theta, float phi) {
  const float s = std::sin(theta);
  return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

}  // namespace

MicrofacetTabulation MicrofacetTabulation::conductor(const ComplexIorSpectra& ior, float alpha, float first_nm,
                                                     float last_nm, float step_nm) {
  MicrofacetTabulation t;
  t.distribution = TrowbridgeReitz(alpha, alpha);
  for (float nm = first_nm; nm <= last_nm; nm += step_nm) {
    const SampledWavelengths one(Float4(nm), Float4(1.0f));
    t.wavelengths_nm.push_back(nm);
    t.n.push_back(ior.n->sample(one)[0]);
    t.k.push_back(ior.k->sample(one)[0]);
  }
  return t;
}

std::map<std::string, TensorFile::Field> tabulate_microfacet_brdf(const MicrofacetTabulation& t) {
  assert(t.wavelengths_nm.size() == t.n.size() && t.n.size() == t.k.size() && t.theta_i_count >= 2);
  const TrowbridgeReitz& ggx = t.distribution;
  const auto u_at = [](int i, int count) { return float(i) / float(count - 1); };

  std::vector<float> theta_i(size_t(t.theta_i_count));
  for (int i = 0; i < t.theta_i_count; ++i)
    theta_i[size_t(i)] = MeasuredBrdf::u_to_theta(u_at(i, t.theta_i_count) * MeasuredBrdf::theta_to_u(t.max_theta_i));

  // ndf and sigma over (u_φ: 2 rows, u_θ): isotropic, so both rows alike.
  std::vector<float> ndf, sigma;
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < t.ndf_size; ++i) {
      const float theta = MeasuredBrdf::u_to_theta(u_at(i, t.ndf_size));
      const Vec3 w = direction(theta, 0.0f);
      ndf.push_back(ggx.d(w));
      // σ(ω) = cos θ (1 + Λ(ω)). At the horizon Λ is infinite while cos θ · Λ stays finite: the last grid point
      // takes the value just above it (θ = 1.5707).
      const Vec3 w_sigma = direction(std::min(theta, 1.5707f), 0.0f);
      sigma.push_back(w_sigma.z * (1.0f + ggx.lambda(w_sigma)));
    }

  const int n = t.vndf_size;
  const size_t grid = size_t(n) * size_t(n), n_lambda = t.wavelengths_nm.size();
  std::vector<float> vndf(size_t(t.theta_i_count) * grid), luminance(size_t(t.theta_i_count) * grid),
      spectra(size_t(t.theta_i_count) * n_lambda * grid);
  for (int k = 0; k < t.theta_i_count; ++k) {
    const Vec3 wo = direction(theta_i[size_t(k)], 0.0f);
    const float sigma_o = wo.z * (1.0f + ggx.lambda(wo));
    // The visible-normal density over the square of ωm (φ relative to ωo's, which is 0 here).
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float u_theta = u_at(x, n), theta_m = MeasuredBrdf::u_to_theta(u_theta);
        const Vec3 wm = direction(theta_m, MeasuredBrdf::u_to_phi(u_at(y, n)));
        const float jacobian = 2.0f * std::numbers::pi_v<float> * std::numbers::pi_v<float> * u_theta * std::sin(theta_m);
        vndf[size_t(k) * grid + size_t(y) * size_t(n) + size_t(x)] = ggx.d(wm) * std::max(0.0f, dot(wo, wm)) / sigma_o * jacobian;
      }
    // S at the points the warp maps the spectral grid to.
    const BilinearWarp2D warp(std::span<const float>(vndf.data() + size_t(k) * grid, grid), n, n, {}, BilinearWarp2D::Use::warp);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const Vec2 u_wm = warp.sample({u_at(x, n), u_at(y, n)}, {}).p;
        const Vec3 wm = direction(MeasuredBrdf::u_to_theta(u_wm.x), MeasuredBrdf::u_to_phi(u_wm.y));
        const Vec3 wi = reflect(wo, wm);
        double mean = 0.0;
        for (size_t l = 0; l < n_lambda; ++l) {
          float s = 0.0f;
          if (wi.z > 0.0f) {
            const float f = fresnel_conductor(Float4(dot(wo, wm)), Float4(t.n[l]), Float4(t.k[l]))[0];
            s = f * ggx.g2(wo, wi) / ggx.g1(wo);
          }
          spectra[((size_t(k) * n_lambda + l) * size_t(n) + size_t(y)) * size_t(n) + size_t(x)] = s;
          mean += s;
        }
        // The luminance warp must give every point some density: a small floor where S is 0 (below the horizon).
        luminance[size_t(k) * grid + size_t(y) * size_t(n) + size_t(x)] = float(mean / double(n_lambda)) + 1e-3f;
      }
  }

  std::map<std::string, TensorFile::Field> fields;
  const uint64_t ti = uint64_t(t.theta_i_count), nn = uint64_t(n);
  fields["theta_i"] = TensorFile::float_field({ti}, theta_i);
  fields["phi_i"] = TensorFile::float_field({1}, {0.0f});
  fields["wavelengths"] = TensorFile::float_field({n_lambda}, t.wavelengths_nm);
  fields["ndf"] = TensorFile::float_field({2, uint64_t(t.ndf_size)}, ndf);
  fields["sigma"] = TensorFile::float_field({2, uint64_t(t.ndf_size)}, sigma);
  fields["vndf"] = TensorFile::float_field({1, ti, nn, nn}, vndf);
  fields["luminance"] = TensorFile::float_field({1, ti, nn, nn}, luminance);
  fields["spectra"] = TensorFile::float_field({1, ti, n_lambda, nn, nn}, spectra);
  TensorFile::Field description;
  description.type = TensorFile::ElementType::uint8;
  const std::string text = "Rimu: a GGX conductor tabulated in the form of Dupuy & Jakob 2018";
  description.shape = {text.size()};
  description.bytes = text;
  fields["description"] = description;
  TensorFile::Field jacobian;
  jacobian.type = TensorFile::ElementType::uint8;
  jacobian.shape = {1};
  jacobian.bytes = std::string(1, '\1');
  fields["jacobian"] = jacobian;
  return fields;
}

}  // namespace rimu
