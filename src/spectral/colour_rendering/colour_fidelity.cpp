#include "spectral/colour_rendering/colour_fidelity.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/error.h"

namespace rimu {
namespace {

constexpr const char* kCesFile = "spectra/reflectances/cie_224_2017_ces_5nm.csv";
constexpr double kFirst_nm = 380.0, kLast_nm = 780.0, kStep_nm = 5.0;
constexpr int kGridCount = 81;  // 380, 385, …, 780 nm
constexpr double kBlendStart_k = 4000.0, kBlendEnd_k = 5000.0;

double grid_nm(int i) { return kFirst_nm + kStep_nm * i; }

/// Σ over the grid of power·reflectance·(x̄, ȳ, z̄)₁₀, scaled by k.
Xyz sample_xyz(const std::vector<double>& power, const TabulatedSpectrum* reflectance, const Observer& o, double k) {
  Xyz sum;
  for (int i = 0; i < kGridCount; ++i) {
    const double nm = grid_nm(i);
    const double w = power[size_t(i)] * (reflectance ? reflectance->value(nm) : 1.0);
    sum.x += w * o.x_bar.value(nm);
    sum.y += w * o.y_bar.value(nm);
    sum.z += w * o.z_bar.value(nm);
  }
  return {k * sum.x, k * sum.y, k * sum.z};
}

/// CAM02-UCS J'a'b' of the 99 samples under a source, relative to its own white at Y10 = 100.
std::vector<Jab> sample_jab(const std::vector<double>& power, const std::vector<TabulatedSpectrum>& samples,
                            const Observer& o) {
  const Xyz white_raw = sample_xyz(power, nullptr, o, 1.0);
  const double k = 100.0 / white_raw.y;
  const Cam02Ucs model(Xyz{k * white_raw.x, 100.0, k * white_raw.z});
  std::vector<Jab> out;
  for (const auto& s : samples) out.push_back(model.jab(sample_xyz(power, &s, o, k)));
  return out;
}

double polygon_area(const std::array<HueBin, kTm30HueBins>& bins, bool test) {
  double twice = 0;
  for (int j = 0; j < kTm30HueBins; ++j) {
    const HueBin& p = bins[size_t(j)];
    const HueBin& q = bins[size_t((j + 1) % kTm30HueBins)];
    const double xa = test ? p.test_a : p.reference_a, ya = test ? p.test_b : p.reference_b;
    const double xb = test ? q.test_a : q.reference_a, yb = test ? q.test_b : q.reference_b;
    twice += xa * yb - xb * ya;
  }
  return 0.5 * std::abs(twice);
}

}  // namespace

double fidelity_from_delta_e(double mean_delta_e) {
  // CIE 224:2017 eq. (9): scale factor 6.73 (calibrated so the CIE F-series average matches CIE 13.3's Ra),
  // then log(exp(x) + 1) so that very poor sources stay above 0 instead of going negative.
  return 10.0 * std::log(std::exp((100.0 - 6.73 * mean_delta_e) / 10.0) + 1.0);
}

ColourFidelityEvaluator::ColourFidelityEvaluator(SpectralLibrary& library)
    : observer_10_(library.observer(StandardObserver::cie1964_10deg)),
      observer_2_(library.observer(StandardObserver::cie1931_2deg)),
      locus_(observer_2_),
      daylight_basis_(library.daylight_basis()) {
  const CsvTable& table = library.table(kCesFile);
  for (int i = 1; i <= kCesCount; ++i) {
    const std::string column = (i < 10 ? "CES0" : "CES") + std::to_string(i);
    samples_.push_back(TabulatedSpectrum::from_csv(table, column, Extrapolation::clamp));
  }
}

std::vector<double> ColourFidelityEvaluator::reference_power(double cct_k, std::string* description) const {
  std::vector<double> planck(kGridCount), daylight(kGridCount);
  if (cct_k < kBlendEnd_k) {
    const BlackbodySpectrum b(cct_k, BlackbodySpectrum::Scale::peak_one);
    for (int i = 0; i < kGridCount; ++i) planck[size_t(i)] = b.value(grid_nm(i));
  }
  if (cct_k >= kBlendStart_k) {
    const TabulatedSpectrum d = daylight_spectrum(daylight_basis_, cct_k, DaylightRounding::exact);
    for (int i = 0; i < kGridCount; ++i) daylight[size_t(i)] = d.value(grid_nm(i));
  }
  if (cct_k < kBlendStart_k) {
    if (description) *description = "Planckian";
    return planck;
  }
  if (cct_k >= kBlendEnd_k) {
    if (description) *description = "CIE daylight";
    return daylight;
  }
  // Between 4000 and 5000 K: each scaled to Y = 1 (CIE 1931 2°, as the CIE calculator does), then mixed.
  const double m = (cct_k - kBlendStart_k) / (kBlendEnd_k - kBlendStart_k);
  const Observer& two = observer_2_;
  auto y_of = [&](const std::vector<double>& p) {
    double y = 0;
    for (int i = 0; i < kGridCount; ++i) y += p[size_t(i)] * two.y_bar.value(grid_nm(i));
    return y;
  };
  const double yp = y_of(planck), yd = y_of(daylight);
  std::vector<double> mix(kGridCount);
  for (int i = 0; i < kGridCount; ++i)
    mix[size_t(i)] = (1.0 - m) * planck[size_t(i)] / yp + m * daylight[size_t(i)] / yd;
  if (description) {
    std::ostringstream text;
    text << "Planckian/daylight blend, m = " << m;
    *description = text.str();
  }
  return mix;
}

ColourFidelity ColourFidelityEvaluator::evaluate(const Spectrum& test_source) const {
  if (const auto* table = dynamic_cast<const TabulatedSpectrum*>(&test_source)) {
    const auto& l = table->wavelengths_nm();
    if (l.front() > kFirst_nm + 1e-6 || l.back() < kLast_nm - 1e-6)
      throw InputError({}, "the colour fidelity index needs the source from 380 to 780 nm (CIE 224:2017); '" +
                               table->describe() + "' covers " + std::to_string(int(l.front())) + "-" +
                               std::to_string(int(l.back())) + " nm");
  }
  std::vector<double> test(kGridCount);
  for (int i = 0; i < kGridCount; ++i) test[size_t(i)] = test_source.value(grid_nm(i));

  ColourFidelity result;
  const Observer& two = observer_2_;
  Xyz xyz2;
  for (int i = 0; i < kGridCount; ++i) {
    const double nm = grid_nm(i);
    xyz2.x += test[size_t(i)] * two.x_bar.value(nm);
    xyz2.y += test[size_t(i)] * two.y_bar.value(nm);
    xyz2.z += test[size_t(i)] * two.z_bar.value(nm);
  }
  result.cct = locus_.cct_duv(uv1960_of(xyz2));
  if (result.cct.validity == CctValidity::below_range || result.cct.validity == CctValidity::above_range)
    throw InputError({}, "the colour fidelity index needs a source with a CCT in 1000-25000 K; '" +
                             test_source.describe() + "' has none");
  const std::vector<double> reference = reference_power(result.cct.cct_k, &result.reference);

  const std::vector<Jab> t = sample_jab(test, samples_, observer_10_);
  const std::vector<Jab> r = sample_jab(reference, samples_, observer_10_);
  double sum_de = 0;
  std::array<double, kTm30HueBins> bin_de{};
  const double bin_width = 2.0 * std::numbers::pi / kTm30HueBins;
  for (int i = 0; i < kCesCount; ++i) {
    const Jab& a = t[size_t(i)];
    const Jab& b = r[size_t(i)];
    const double de = std::sqrt((a.j - b.j) * (a.j - b.j) + (a.a - b.a) * (a.a - b.a) + (a.b - b.b) * (a.b - b.b));
    sum_de += de;
    result.sample_fidelity[size_t(i)] = fidelity_from_delta_e(de);
    // Bins by the sample's hue under the reference (TM-30-20 §4.3).
    double h = std::atan2(b.b, b.a);
    if (h < 0) h += 2.0 * std::numbers::pi;
    const int bin = std::min(kTm30HueBins - 1, int(h / bin_width));
    HueBin& hb = result.bins[size_t(bin)];
    ++hb.sample_count;
    hb.reference_a += b.a;
    hb.reference_b += b.b;
    hb.test_a += a.a;
    hb.test_b += a.b;
    bin_de[size_t(bin)] += de;
  }
  result.rf = fidelity_from_delta_e(sum_de / kCesCount);
  for (int j = 0; j < kTm30HueBins; ++j) {
    HueBin& hb = result.bins[size_t(j)];
    if (hb.sample_count == 0) continue;  // never with the 99 CES: every bin holds at least 3
    const double n = hb.sample_count;
    hb.reference_a /= n;
    hb.reference_b /= n;
    hb.test_a /= n;
    hb.test_b /= n;
    hb.fidelity = fidelity_from_delta_e(bin_de[size_t(j)] / n);
    const double chroma = std::hypot(hb.reference_a, hb.reference_b);
    const double hue = (j + 0.5) * bin_width;  // TM-30-20: shifts are measured along the bin's bisecting angle
    const double da = hb.test_a - hb.reference_a, db = hb.test_b - hb.reference_b;
    hb.chroma_shift = (da * std::cos(hue) + db * std::sin(hue)) / chroma;
    hb.hue_shift = (-da * std::sin(hue) + db * std::cos(hue)) / chroma;
  }
  result.rg = 100.0 * polygon_area(result.bins, true) / polygon_area(result.bins, false);
  return result;
}

std::string colour_fidelity_text(const ColourFidelity& f, const std::string& description) {
  std::ostringstream out;
  char line[200];
  out << "spectrum           " << description << "\n";
  std::snprintf(line, sizeof line, "Rf (CIE 224:2017)  %.1f\nRg (TM-30-20)      %.1f\n", f.rf, f.rg);
  out << line;
  std::snprintf(line, sizeof line, "CCT                %.1f K   Duv %.5f\n", f.cct.cct_k, f.cct.duv);
  out << line << "reference          " << f.reference << "\n";
  out << "hue bin  samples  Rf,h   Rcs,h    Rhs,h\n";
  for (int j = 0; j < kTm30HueBins; ++j) {
    const HueBin& b = f.bins[size_t(j)];
    std::snprintf(line, sizeof line, "%7d  %7d  %5.1f  %+5.1f%%  %+6.3f\n", j + 1, b.sample_count, b.fidelity,
                  100.0 * b.chroma_shift, b.hue_shift);
    out << line;
  }
  return out.str();
}

std::string colour_fidelity_json(const ColourFidelity& f, const std::string& description) {
  nlohmann::ordered_json j;
  j["spectrum"] = description;
  j["rf"] = f.rf;
  j["rg"] = f.rg;
  j["cct_k"] = f.cct.cct_k;
  j["duv"] = f.cct.duv;
  j["reference"] = f.reference;
  nlohmann::ordered_json bins = nlohmann::ordered_json::array();
  for (const HueBin& b : f.bins)
    bins.push_back({{"samples", b.sample_count},
                    {"rf", b.fidelity},
                    {"chroma_shift", b.chroma_shift},
                    {"hue_shift", b.hue_shift},
                    {"reference_ab", {b.reference_a, b.reference_b}},
                    {"test_ab", {b.test_a, b.test_b}}});
  j["hue_bins"] = bins;
  j["sample_rf"] = f.sample_fidelity;
  return j.dump(2) + "\n";
}

}  // namespace rimu
