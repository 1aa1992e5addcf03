// How a user names the observer and the tristimulus method, read the same way by the tools (--observer, --method)
// and the Python module (observer=, method=); the caller says where the value came from.
#pragma once

#include <optional>
#include <string>

#include "spectral/error.h"
#include "spectral/library/spectral_library.h"
#include "spectral/colorimetry/tristimulus_method.h"

namespace rimu {

/// 2 (CIE 1931 2°) or 10 (CIE 1964 10°). Throws InputError at `where` for any other number.
StandardObserver standard_observer_option(int degrees, const SourceLocation& where);

/// "auto" or "" (the default for the data's spacing: empty result), native, 1nm or astm-e308. Throws InputError at
/// `where` for any other text.
std::optional<TristimulusMethod> tristimulus_method_option(const std::string& text, const SourceLocation& where);

}  // namespace rimu
