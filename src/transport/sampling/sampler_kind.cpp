// The sampler factory: SamplerKind → Sampler (declared in sampler.h).
#include "transport/sampling/sampler.h"
#include "transport/sampling/sobol_sampler.h"

namespace rimu {

std::unique_ptr<Sampler> make_sampler(SamplerKind kind, uint64_t seed) {
  switch (kind) {
    case SamplerKind::independent: return std::make_unique<IndependentSampler>(seed);
    case SamplerKind::sobol: return std::make_unique<SobolSampler>(seed);
  }
  return std::make_unique<SobolSampler>(seed);
}

const char* sampler_kind_name(SamplerKind kind) {
  return kind == SamplerKind::independent ? "independent" : "sobol";
}

std::optional<SamplerKind> parse_sampler_kind(std::string_view name) {
  if (name == "independent") return SamplerKind::independent;
  if (name == "sobol") return SamplerKind::sobol;
  return std::nullopt;
}

}  // namespace rimu
