// A load-time check that every light gets a fair share of the light samples where it matters most.
//
// For each finite light, a probe point: the first surface hit by a ray from the light's centre along its emission
// axis (a spot's or IES light's axis, an emissive mesh's power-weighted mean normal; for a point light or a closed
// mesh, whichever of the six axis directions hits a surface nearest). There, with the surface's normal facing the
// light, two shares are estimated:
//   the sample share P: the probability that the scene's light sampler picks this light (any of its parts) there,
//     exact (Σ pmf) for lights of up to 64 parts, else from 4,096 stratified draws;
//   the irradiance share S: this light's unshadowed direct irradiance there over that of all lights
//     (its own from 16 stratified light samples; the others' from 256 draws of the sampler itself, which is an
//     unbiased estimate of their sum), at 450, 500, 550 and 600 nm averaged.
// The light is reported when P < 1 % and P < S/10: it gets under 1 % of the light samples at the place it lights,
// and at least ten times fewer than its contribution there deserves (so a ceiling of a thousand panels, each with a
// small share of the light below it, does not warn). Only the first 2,000 finite lights are checked.
#pragma once

#include <string>
#include <vector>

#include "render/scene/scene.h"

namespace rimu {

struct LightCoverage {
  int light = 0;
  Vec3 probe_m;
  double sample_share = 0.0;      ///< P above
  double irradiance_share = 0.0;  ///< S above
  bool starved() const { return sample_share < 0.01 && sample_share < 0.1 * irradiance_share; }
};

/// P and S (above) for each finite light that has a probe point, in light order.
std::vector<LightCoverage> light_coverage(const Scene& scene);
/// One message per starved light, naming it (Scene::light_names) and the numbers.
std::vector<std::string> light_coverage_warnings(const Scene& scene);

}  // namespace rimu
