// The settings of Metropolis light transport (render/metropolis_renderer.h), part of the integrator's settings.
#pragma once

namespace rimu {

/// Settings of the Metropolis render loop (docs/transport.md, "Metropolis light transport").
struct MetropolisSettings {
  /// Independent paths per pixel that estimate the image's total brightness b and from which chains start.
  float bootstrap_per_pixel = 4.0f;
  /// Markov chains (at most one per mutation); fixed, so that the image does not depend on the threads.
  int chains = 1024;
  /// The standard deviation of a small step in each primary-sample dimension.
  float sigma = 0.01f;
  /// The probability of a large step (a fresh independent sample).
  float large_step_probability = 0.3f;
  /// The large steps' proposals also count as uniform samples, weighted against the chain by the balance heuristic
  /// (Kelemen et al. 2002): dim pixels, which the chains rarely visit, get their share of independent samples.
  bool large_step_mis = true;
  /// The chains' paths are bidirectional path tracing's (a camera and a light subpath from one point, every join
  /// weighted by MIS) where it can run (a camera light subpaths join: pinhole or thin lens; no media), else the path
  /// tracer's.
  bool bidirectional = true;
  /// The chains sample paths in proportion to their brightness up to this multiple of the bootstrap's mean
  /// brightness, and in proportion to that cap above it (a brighter path splats more than the others); 0: no cap.
  float brightness_cap = 64.0f;
};

}  // namespace rimu
