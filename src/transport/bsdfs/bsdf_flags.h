// What kinds of lobes a BSDF has: what the integrator may do with it.
#pragma once

namespace rimu {

/// Properties of a BSDF that the integrator branches on.
struct BsdfFlags {
  /// Some lobe is a Dirac delta (perfect mirror or refraction): it can only be sampled, never evaluated.
  bool has_delta = false;
  /// eval()/pdf() are non-zero somewhere: next-event estimation (with MIS) is worth doing.
  bool has_non_delta = false;
  /// wi may lie on the other side of the surface from wo. The integrator must keep the geometric side (the
  /// BSDF uses the sign of wo.z to know whether the ray is inside); opaque BSDFs (false) are two-sided, and the
  /// integrator may flip their shading frame so that wo.z > 0.
  bool has_transmission = false;
  /// A non-delta lobe narrow enough (TrowbridgeReitz::is_glossy) that what it passes from a light depends more on
  /// the light's direction than on its irradiance: next-event estimation then resamples its choice of light among
  /// a few candidates by that (transport/integrators/light_resampling.h).
  bool has_glossy = false;
};

}  // namespace rimu
