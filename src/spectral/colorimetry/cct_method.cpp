#include "spectral/colorimetry/cct_method.h"

#include <string>

namespace rimu {

CctMethod cct_method_from_name(std::string_view name, const SourceLocation& where) {
  if (name == "ohno2013") return CctMethod::ohno2013;
  if (name == "robertson1968") return CctMethod::robertson1968;
  throw InputError(where, "unknown CCT method '" + std::string(name) +
                              "': expected ohno2013 (Ohno 2013, the default) or robertson1968 (Robertson 1968)");
}

const char* cct_validity_name(CctValidity validity, CctMethod method) {
  if (method == CctMethod::ohno2013) return cct_validity_name(validity);
  switch (validity) {
    case CctValidity::ok: return "ok";
    case CctValidity::below_range: return "below 1667 K";
    case CctValidity::above_range: return "bluer than an infinite temperature";
    case CctValidity::far_from_locus: return "|Duv| > 0.05";
  }
  return "unknown";
}

}  // namespace rimu
