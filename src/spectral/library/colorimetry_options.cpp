#include "spectral/library/colorimetry_options.h"

namespace rimu {

StandardObserver standard_observer_option(int degrees, const SourceLocation& where) {
  if (degrees == 2) return StandardObserver::cie1931_2deg;
  if (degrees == 10) return StandardObserver::cie1964_10deg;
  throw InputError(where, "expected 2 or 10 (CIE 1931 2° or CIE 1964 10°), got " + std::to_string(degrees));
}

std::optional<TristimulusMethod> tristimulus_method_option(const std::string& text, const SourceLocation& where) {
  if (text.empty() || text == "auto") return std::nullopt;
  if (auto m = parse_tristimulus_method(text)) return m;
  throw InputError(where, "unknown tristimulus method '" + text + "'; use auto, native, 1nm or astm-e308");
}

}  // namespace rimu
