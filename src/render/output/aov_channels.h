// The feature buffers as EXR layers (`rimu --aov albedo,normal,depth,variance,halves`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "render/film/feature_buffers.h"
#include "render/film/film.h"

namespace rimu {

/// Which feature layers a render writes. Each feature's layer comes with the variance of its mean.
struct AovSelection {
  bool albedo = false, normal = false, depth = false, variance = false, halves = false;
  bool any() const { return albedo || normal || depth || variance || halves; }
  static AovSelection all() { return {true, true, true, true, true}; }
};

/// Parses "albedo,normal,depth,variance,halves" (any of them, in any order) or "all". InputError naming `where`
/// (an option or a scene key) for an unknown or repeated name or an empty list.
AovSelection parse_aov_list(const std::string& text, const std::string& where);
std::string aov_list_text(const AovSelection& selection);

/// The layers, each a value per pixel of the film's crop window, row by row (ExrOptions::extra_channels). With
/// c0, c1, c2 the film's channel names (X, Y, Z or R, G, B):
/// - albedo: "albedo.c0" … "albedo.c2" (feature_albedo_channels: reflectance, 1 for white, no exposure) and
///   "albedo_variance";
/// - normal: "N.X", "N.Y", "N.Z" (world space, the mean of the samples' unit normals) and "N_variance";
/// - depth: "depth.Z" (scene units along the path, through mirrors and glass; not a bare "Z", which is the XYZ
///   beauty's third channel) and "depth_variance";
/// - variance: "variance", the variance of the written beauty's mean, its three channels averaged;
/// - halves: "half_even.c0" … and "half_odd.c0" …, the means of the even- and odd-indexed samples as the beauty is
///   written (the film's output transform applied), which the denoiser filters against each other.
/// Pixels without samples are 0; every value is finite.
std::vector<std::pair<std::string, std::vector<float>>> aov_channels(const FeatureBuffers& features, const Film& film,
                                                                      const AovSelection& selection);

}  // namespace rimu
