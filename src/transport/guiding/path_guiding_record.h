// What one camera path teaches the guiding field: for each guidable vertex, the luminance that arrived along the
// direction the path left it by (everything the estimator added after that bounce, divided by the throughput up
// to and including it), recorded when the path ends.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/guiding/guiding_field.h"

namespace rimu {

/// The luminance weights of the four lanes: ȳ(λⱼ)/(4·p(λⱼ)), so that Σⱼ wⱼ Lⱼ estimates the luminance (per 683 lm/W)
/// of the radiance the lanes carry, as the film would see it. ȳ is the two-lobe fit of Wyman, Sloan & Shirley,
/// "Simple Analytic Approximations to the CIE XYZ Color Matching Functions" (JCGT 2(2), 2013): guiding only needs
/// a shape, not the tabulated observer. `rgb`: the lanes carry linear sRGB, weighted by its luminance row.
Float4 guiding_lane_weights(const SampledWavelengths& lambda, bool rgb);

class PathGuidingRecord {
 public:
  static constexpr int kMaxVertices = 32;  ///< deeper vertices are not recorded (they still render)

  explicit PathGuidingRecord(Float4 lane_weights) : lane_weights_(lane_weights) {}

  /// A vertex left along `direction` with hero density `pdf`; `throughput` is the path throughput after the bounce
  /// (what later contributions are multiplied by), per lane; `cosine` = |cos θ| of `direction` to the surface.
  /// The sample's weight is luminance · cosine / pdf: the field learns the light's share of the irradiance, L·cos
  /// (the product a diffuse vertex would ideally sample), not of the radiance, which would spend guided rays on
  /// grazing directions that contribute little (docs/transport.md, "Path guiding").
  /// False when the record is full (the vertex is not recorded).
  bool add_vertex(Vec3 position, int facing, Vec3 direction, float pdf, float cosine, const SampledSpectrum& throughput);
  /// A contribution the estimator adds to the pixel: it arrived at every recorded vertex. `skip_last`: not at the
  /// last one (an emitter its own ray hit, which next-event estimation samples: path_integrator.cpp).
  void add_radiance(const SampledSpectrum& contribution, bool skip_last = false);
  /// The ray leaving the last recorded vertex travelled `t` further (a hit; panes passed add up) or escaped: the
  /// distance of the light it brought (GuidingSample::distance). Ignored once a later vertex is recorded. Called
  /// only for mixture fields (path_integrator.cpp); without it a vertex's distance is recorded as ∞.
  void travel(float t) {
    if (count_ > 0 && vertices_[size_t(count_ - 1)].open) vertices_[size_t(count_ - 1)].distance += t;
  }
  void escape() {
    if (count_ > 0 && vertices_[size_t(count_ - 1)].open) vertices_[size_t(count_ - 1)].distance = INFINITY;
  }
  /// Appends the vertices' samples to `out`.
  void flush(std::vector<GuidingSample>& out) const;

 private:
  struct Vertex {
    Vec3 position;
    int facing = 0;
    Vec2 square;
    float cosine_over_pdf = 0.0f;
    SampledSpectrum inverse_throughput;  ///< 1/throughput per lane (0 in lanes that carry nothing)
    SampledSpectrum incident;            ///< the radiance that arrived so far, per lane
    float distance = 0.0f;               ///< to the next vertex (travel, escape)
    bool open = true;                    ///< the path has not reached its next recorded vertex yet
  };
  Float4 lane_weights_;
  std::array<Vertex, kMaxVertices> vertices_;
  int count_ = 0;
};

}  // namespace rimu
