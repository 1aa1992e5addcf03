#include "render/time_budget.h"

namespace rimu {

bool TimeBudget::allows_pass(double elapsed_s, double pass_samples, bool film_empty) {
  const double used_s = spent_s_ + elapsed_s;
  bool allowed = film_empty;
  if (!allowed) {
    if (pass_start_s_ < 0.0 || pass_samples_ <= 0) {
      allowed = used_s < limit_s_;
    } else {
      const double seconds_per_sample = (elapsed_s - pass_start_s_) / pass_samples_;
      allowed = used_s + seconds_per_sample * pass_samples <= limit_s_;
    }
  }
  if (!allowed) {
    spent_ = true;
    return false;
  }
  pass_start_s_ = elapsed_s;
  pass_samples_ = pass_samples;
  return true;
}

}  // namespace rimu
