// A participating medium of any kind, and which medium a path is in (the medium stack).
#pragma once

#include <array>
#include <memory>
#include <variant>

#include "transport/media/grid_medium.h"
#include "transport/media/homogeneous_medium.h"
#include "transport/media/medium_emission.h"
#include "transport/media/noise_cloud_medium.h"
#include "transport/media/textured_albedo.h"

namespace rimu {

/// A homogeneous, voxel-grid or procedural (noise cloud) medium, held by value, with the priority that resolves
/// overlaps (see MediumStack) and whether its scattering events count towards the path's max_depth.
class Medium {
 public:
  using Variant = std::variant<HomogeneousMedium, GridMedium, NoiseCloudMedium>;

  template <typename T>
  explicit Medium(T medium, int priority = 0, bool counts_towards_max_depth = true)
      : medium_(std::move(medium)), priority_(priority), counts_towards_max_depth_(counts_towards_max_depth) {}

  const HenyeyGreenstein& phase() const {
    return std::visit([](const auto& m) -> const HenyeyGreenstein& { return m.phase(); }, medium_);
  }
  int priority() const { return priority_; }
  /// Whether the vertices of a path inside this medium count towards max_depth (its scattering events when the
  /// integrator counts media, VolumetricIntegratorSettings::max_depth_includes_media; the surfaces a path hits
  /// from inside it, its boundary's internal reflections or anything embedded in it, always). False for a subsurface walk under a dielectric: the walk belongs to the vertex where the path
  /// entered, as pbrt-v4 spends one bounce on a BSSRDF however often light scatters and reflects beneath it; a
  /// walk of dozens of events cut at pbrt's usual max depth of 5 would leave a translucent object nearly black.
  bool counts_towards_max_depth() const { return counts_towards_max_depth_; }
  const HomogeneousMedium* homogeneous() const { return std::get_if<HomogeneousMedium>(&medium_); }
  const GridMedium* grid() const { return std::get_if<GridMedium>(&medium_); }
  const NoiseCloudMedium* noise_cloud() const { return std::get_if<NoiseCloudMedium>(&medium_); }
  /// σ_a per unit density (1/m; the medium's σ_a for a homogeneous one).
  const SpectrumPtr& sigma_a() const {
    return std::visit([](const auto& m) -> const SpectrumPtr& { return m.sigma_a(); }, medium_);
  }
  /// A surface albedo texture over the boundary (TexturedAlbedo; null: none): a subsurface medium's colour map.
  const TexturedAlbedo* textured_albedo() const { return textured_albedo_.get(); }
  void set_textured_albedo(std::shared_ptr<const TexturedAlbedo> albedo) { textured_albedo_ = std::move(albedo); }
  /// The surface albedo the medium was authored with (Chiang et al. 2016's multiple-scattering albedo A, a
  /// texture or a constant; null for σ_a/σ_s media): what an object of it looks like, reported as the albedo feature
  /// where a camera ray meets its boundary (path_features.h).
  const SpectralTexture* surface_albedo() const { return surface_albedo_.get(); }
  void set_surface_albedo(SpectralTexturePtr albedo) { surface_albedo_ = std::move(albedo); }
  /// The light the medium emits (MediumEmission; null: none), and the light group it is credited to.
  const MediumEmission* emission() const { return emission_.get(); }
  int emission_light_group() const { return emission_light_group_; }
  void set_emission(std::shared_ptr<const MediumEmission> emission, int light_group) {
    emission_ = std::move(emission);
    emission_light_group_ = light_group;
  }
  void set_emission_light_group(int light_group) { emission_light_group_ = light_group; }

 private:
  Variant medium_;
  int priority_;
  bool counts_towards_max_depth_;
  std::shared_ptr<const TexturedAlbedo> textured_albedo_;
  SpectralTexturePtr surface_albedo_;
  std::shared_ptr<const MediumEmission> emission_;
  int emission_light_group_ = 0;
};

/// What a surface does to the medium stack: the medium enclosed by the shape (−1: none) and whether the surface
/// is an index-matched boundary (no BSDF: rays and shadow rays cross it unchanged). Indexed by material.
struct MediumBoundary {
  int interior_medium = -1;
  bool index_matched = false;
};

/// The media a path is inside, innermost entry last. Entering a closed shape through its front face pushes its
/// interior medium; leaving through its back face removes that medium's most recent entry. Where shapes
/// overlap (nested or intersecting), the CURRENT medium is the entry of highest priority, the most recently
/// entered one among equals (the priority rule of Schmidt & Budge 2002, "Simple Nested Dielectrics in Ray
/// Traced Images", without their false-interface skipping: a boundary always applies its own BSDF).
/// A camera path starts with the scene's camera medium, if any (VolumetricScene::camera_medium). Fixed capacity:
/// deeper nesting than kCapacity keeps the innermost kCapacity entries.
class MediumStack {
 public:
  static constexpr int kCapacity = 8;

  /// The current medium index, or −1 for vacuum.
  int current(const std::vector<Medium>& media) const {
    int best = -1;
    for (int i = 0; i < size_; ++i)
      if (best < 0 || media[size_t(entries_[i])].priority() >= media[size_t(best)].priority()) best = entries_[i];
    return best;
  }
  /// Crossing the boundary of `medium` (entering if `entering`, else leaving).
  void cross(int medium, bool entering) {
    if (medium < 0) return;
    if (entering) {
      if (size_ == kCapacity) {
        for (int i = 1; i < size_; ++i) entries_[i - 1] = entries_[i];
        --size_;
      }
      entries_[size_++] = medium;
      return;
    }
    for (int i = size_ - 1; i >= 0; --i)
      if (entries_[i] == medium) {
        for (int j = i + 1; j < size_; ++j) entries_[j - 1] = entries_[j];
        --size_;
        return;
      }
    // Leaving a medium never entered (a camera inside a shape, or an open mesh): nothing to remove.
  }
  int size() const { return size_; }

 private:
  std::array<int, kCapacity> entries_{};
  int size_ = 0;
};

}  // namespace rimu
