// Which method computes a correlated colour temperature: Ohno (2013), Rimu's default, or Robertson (1968).
#pragma once

#include <string_view>

#include <optional>

#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/colorimetry/robertson_cct.h"
#include "spectral/error.h"

namespace rimu {

enum class CctMethod {
  ohno2013,       ///< PlanckianLocus::cct_duv: the exact locus, 1000-25000 K, today's c2 (the default everywhere)
  robertson1968,  ///< RobertsonCct::cct_duv: the 1968 table, 1667 K to infinity, within 0.08 MK⁻¹ of the exact CCT
};

/// "ohno2013" or "robertson1968"; throws InputError at `where` naming both.
CctMethod cct_method_from_name(std::string_view name, const SourceLocation& where);

/// How reports name a CctValidity under `method`: the ranges differ ("below 1000 K" for Ohno's table, "below
/// 1667 K" for Robertson's).
const char* cct_validity_name(CctValidity validity, CctMethod method);

/// One method set up once, then applied to many chromaticities: Ohno's builds its locus table (~5 ms), Robertson's
/// holds its 31 lines.
class CctSolver {
 public:
  /// Ohno (2013) on `observer`'s Planckian locus.
  explicit CctSolver(const Observer& observer) : ohno_(std::in_place, observer) {}
  /// Robertson (1968) on its table (tabulated for the CIE 1931 2° observer only).
  explicit CctSolver(RobertsonCct robertson) : robertson_(std::move(robertson)) {}

  CctMethod method() const { return ohno_ ? CctMethod::ohno2013 : CctMethod::robertson1968; }
  CctDuv cct_duv(Uv1960 uv) const { return ohno_ ? ohno_->cct_duv(uv) : robertson_->cct_duv(uv); }
  const char* validity_name(CctValidity validity) const { return cct_validity_name(validity, method()); }

 private:
  std::optional<PlanckianLocus> ohno_;
  std::optional<RobertsonCct> robertson_;
};

}  // namespace rimu
