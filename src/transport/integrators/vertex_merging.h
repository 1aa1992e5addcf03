// Vertex merging: photon mapping inside bidirectional path tracing, combined with its connections by multiple
// importance sampling (Georgiev, Křivánek, Davidovič & Slusallek 2012, "Light transport simulation with vertex
// connection and merging"; Hachisuka, Pantaleoni & Jensen 2012, "A path space extension for robust light transport
// simulation").
//
// Why. A connection joins one camera vertex to the vertices of one light subpath. Where the light reaches what the
// camera sees only by a rare way in (a room lit through a door ajar) or only by a specular chain seen through another
// (a pool floor seen through rippled water, E S D S L), few light subpaths find it and no connection can join a
// camera path through the specular surfaces. Merging lets every camera vertex use every light vertex of the pass
// that landed within a radius r of it: the light subpaths that found the way in serve all pixels, and a vertex seen
// through a specular surface is reached from both sides. Its cost is a bias that vanishes as r shrinks with the
// passes (r_i = r₁ i^{(α−1)/2}, Knaus & Zwicker 2011; α = 0.75 as Georgiev et al.), so the estimate is consistent,
// not unbiased.
//
// Wavelengths. A light vertex carries its subpath's four wavelengths; a camera vertex can merge only with light
// vertices at its own. Each pass therefore has K sets of wavelengths ("buckets"); every light subpath of the pass
// and every camera sample uses one of them (the camera samples by a hash of their pixel, so that neighbouring pixels
// see different sets), and merges happen within a bucket. More buckets trade light vertices per merge for colour
// noise shared by less of the image; measured, one bucket (as pbrt-v4's SPPM: one set per pass for the whole image)
// is best when the passes' heroes follow a low-discrepancy sequence (the render loop's): 3–3.5× lower relMSE than
// four buckets where merges carry the light (a pool seen through water), equal on the Cornell box.
//
// This file holds one pass's light vertices (what a merge needs of each: where, from where its light came, its
// flux and its subpath's MIS densities) in a hashed uniform grid of cells 2r wide; the bidirectional integrator
// traces the subpaths (BidirectionalPathIntegrator::trace_merge_subpath) and merges
// (BidirectionalPathIntegrator::radiance).
#pragma once

#include <cstdint>
#include <vector>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/geometry/surface_hit.h"
#include "transport/geometry/vector.h"
#include "transport/integrators/bidirectional_mis.h"

namespace rimu {

/// Vertex merging's settings (`"integrator": {"method": "vcm", "merge_radius": …}`).
struct VertexMergingSettings {
  /// r₁ in metres; 0 (the default): 0.002 × the scene's bounding-box diagonal.
  float radius_m = 0.0f;
  float alpha = 0.75f;  ///< the radius shrinks as i^{(α−1)/2} over passes i = 1, 2, …
  int wavelength_buckets = 1;  ///< K, the pass's sets of wavelengths (see the file's comment)
  /// At most this many light subpaths per pass (one per pixel below it, each kept whole for its pixel's joins): bounds
  /// the pass's memory (1–2.6 KiB per subpath measured: docs/transport.md, "Vertex connection and merging").
  int max_light_subpaths = 1 << 18;

  /// The radius of pass `sample_index` (0-based: the film's sample index), for a scene of diagonal `scene_scale`.
  float radius(int sample_index, float scene_scale) const;
};

/// A light subpath's vertex y_i (i ≥ 1) on a surface with a non-delta BSDF, as a merge reads it.
struct MergeVertex {
  Vec3 position{};
  Vec3 w_light{};  ///< unit, world: from y_i back towards y_{i−1} (towards the light for a ray of daylight)
  Vec3 previous_position{};  ///< y_{i−1} (unused when it is at infinity)
  Vec3 previous_normal{};    ///< y_{i−1}'s geometric normal (zero for a lamp at a point)
  SampledSpectrum beta{0.0f};     ///< flux arriving at y_i over the densities that made it (hero-density units)
  SampledSpectrum ratio{1.0f};    ///< the subpath's spectral-MIS ratios
  SampledSpectrum pdf_fwd{0.0f};  ///< y_i's area density from y_{i−1} (1: y_{i−1} left by a delta lobe)
  SampledSpectrum pass_in{1.0f};  ///< the pass probability of the panes between y_{i−1} and y_i
  uint32_t subpath = 0;           ///< index into VertexMergingPass::subpaths
  uint16_t index = 0;             ///< i
  uint16_t bucket = 0;
  bool previous_at_infinity = false;
};

/// What a merge needs of a light subpath as a whole: y₀'s densities for the techniques that start there, and where
/// the MIS densities of its vertices y₀ … y_{m−1} begin in VertexMergingPass::densities.
struct MergeSubpath {
  uint32_t first_density = 0;
  int light = -1;
  float pdf_nee = 0.0f;
  float pdf_emit = 0.0f;
  bool hittable = false;
};

/// A light subpath's vertex kept whole for the camera sample of its pixel, which joins it as it would join a subpath
/// of its own (BidirectionalPathIntegrator::radiance rebuilds a surface vertex's BSDF from `hit` and `wo_world`).
struct StoredLightVertex {
  SurfaceHit hit{};
  Vec3 position{}, normal{};  ///< as the vertex had them (a surface's are rebuilt from the hit)
  Vec3 wo_world{};            ///< a surface's direction back along the subpath
  SampledSpectrum beta{0.0f}, ratio{1.0f}, pdf_fwd{0.0f}, pdf_rev{0.0f}, pass_in{1.0f};
  float pdf_nee = 0.0f, pdf_emit = 0.0f;
  int light = -1;
  uint8_t kind = 0;  ///< the integrator's vertex kind
  bool delta = false, hittable = false;
};

/// The light vertices a group of subpaths left (filled by one task; VertexMergingPass::append joins them in order).
struct MergeVertexBatch {
  std::vector<MergeSubpath> subpaths;
  std::vector<JoinedVertex> densities;
  std::vector<MergeVertex> vertices;
  std::vector<StoredLightVertex> stored;  ///< every subpath's vertices, whole
  std::vector<uint32_t> stored_start;     ///< per subpath of the batch, its first entry in `stored`
  void clear() {
    subpaths.clear();
    densities.clear();
    vertices.clear();
    stored.clear();
    stored_start.clear();
  }
};

/// One pass's light vertices, searchable by position. The batches are the pass's own (filled in place and kept from
/// pass to pass, so their memory is allocated once).
class VertexMergingPass {
 public:
  /// Starts a pass of `light_subpaths` subpaths with merge radius `radius_m` and these wavelength sets.
  void start(float radius_m, std::vector<SampledWavelengths> bucket_wavelengths, int light_subpaths);
  /// The pass's `count` batches, to be filled (each cleared by its filler) in subpath order: batch b holds the
  /// subpaths after those of batches 0 … b−1, so that the pass does not depend on the threads.
  std::vector<MergeVertexBatch>& batches(size_t count) {
    batches_.resize(count);
    return batches_;
  }
  /// Builds the search grid over the batches' vertices.
  void build();

  float radius() const { return radius_; }
  int buckets() const { return int(wavelengths_.size()); }
  const SampledWavelengths& wavelengths(int bucket) const { return wavelengths_[size_t(bucket)]; }
  /// The bucket of light subpath `index`, and of a camera sample of pixel (x, y) in pass `sample_index`.
  int subpath_bucket(int index) const { return index % buckets(); }
  int pixel_bucket(int x, int y, int sample_index) const;
  /// c = π r² N_k: the factor that turns a connection's density into the merge's (N_k: the bucket's subpaths).
  float merge_factor(int bucket) const;

  int light_subpath_count() const { return light_subpaths_; }
  /// Light subpath `index` whole (its vertices y₀ … y_{m−1}; m may be 0), for the camera sample of its pixel.
  const StoredLightVertex* light_subpath(int index, int& length) const;
  size_t vertex_count() const { return order_.size(); }
  size_t memory_bytes() const;

  /// Calls f(vertex, its subpath, the subpath's MIS densities) for each light vertex of `bucket` within the radius of
  /// p, in a fixed order.
  template <typename F>
  void for_each_within(Vec3 p, int bucket, F&& f) const {
    if (order_.empty()) return;
    const float r2 = radius_ * radius_;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = cell_coordinate(p[a] - radius_);
      hi[a] = cell_coordinate(p[a] + radius_);
    }
    // Cells are 2r wide: at most two per axis. Distinct cells may share a slot; each slot is visited once.
    uint32_t visited[8];
    int visited_count = 0;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const uint32_t slot = slot_of(x, y, z, bucket);
          bool seen = false;
          for (int k = 0; k < visited_count; ++k) seen = seen || visited[k] == slot;
          if (seen) continue;
          visited[visited_count++] = slot;
          for (uint32_t k = slot_start_[slot]; k < slot_start_[slot + 1]; ++k) {
            const Entry& e = order_[k];
            if (e.vertex->bucket != bucket || length_squared(e.vertex->position - p) > r2) continue;
            const MergeSubpath& subpath = e.batch->subpaths[e.vertex->subpath];
            f(*e.vertex, subpath, e.batch->densities.data() + subpath.first_density);
          }
        }
  }

 private:
  struct Entry {
    const MergeVertex* vertex;
    const MergeVertexBatch* batch;
  };
  int cell_coordinate(float x) const { return int(std::floor(x * inverse_cell_)); }
  uint32_t slot_of(int x, int y, int z, int bucket) const;

  float radius_ = 0.0f;
  float inverse_cell_ = 0.0f;
  std::vector<SampledWavelengths> wavelengths_;
  std::vector<uint32_t> bucket_subpaths_;  ///< N_k
  int light_subpaths_ = 0;
  std::vector<MergeVertexBatch> batches_;
  std::vector<uint32_t> first_subpath_;  ///< per batch, the index of its first stored subpath (one more: the end)
  std::vector<uint32_t> slot_start_;     ///< per slot, its first entry in order_ (one more entry: the end)
  std::vector<Entry> order_;             ///< the vertices by slot
};

}  // namespace rimu
