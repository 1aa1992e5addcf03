// rimu-e308-weights: computes the ASTM E308 weighting factors of data/e308/ from the CIE 1 nm tables.
//
//   rimu-e308-weights --data <data root> --out <folder>
//
// For each illuminant of SpectralLibrary::e308_illuminant_names() (its 1 nm spectrum from
// SpectralLibrary::e308_illuminant()), both standard observers and 10 and 20 nm, runs compute_e308_weights()
// (src/spectral/colorimetry/astm_e308.h) over 360-830 nm and writes astm_e308_<illuminant>_<2|10>deg_<10|20>nm.csv with the
// command in its first lines, and beside it the Table 5 counterpart (…_table5.csv: the same weights with the
// Stearns & Stearns bandpass correction folded in, e308_table5_from_table6()).
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "spectral/colorimetry/astm_e308.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"

using namespace rimu;

namespace {

/// Where the 1 nm spectrum of `name` comes from (SpectralLibrary::e308_illuminant), for the files' first lines.
std::string source_of(const std::string& name) {
  if (name == "D55")
    return "the S0, S1, S2 basis at 5503 K (CIE 15:2004 3.1, M1 and M2 to 3 decimals), 5 nm, Lagrange-interpolated to 1 nm";
  if (name == "D75")
    return "the S0, S1, S2 basis at 7504 K (CIE 15:2004 3.1, M1 and M2 to 3 decimals), 5 nm, Lagrange-interpolated to 1 nm";
  if (name == "F2" || name == "F7" || name == "F11")
    return "the CIE 15:2004 Table T.6 5 nm table (cie_f1_f12_5nm.csv), Lagrange-interpolated to 1 nm";
  if (name == "A") return "the CIE 1 nm table (cie_a_1nm.csv)";
  if (name == "D50")
    return "the CIE 5 nm table (cie_d50_5nm.csv), Lagrange-interpolated to 1 nm (this, not the CIE 1 nm table, "
           "reproduces E308's white points)";
  if (name == "C")
    return "CIE 15:2004 Table T.1 (cie_c_5nm.csv, 320-780 nm), Lagrange-interpolated to 1 nm, held at its 780 nm "
           "value beyond";
  if (name == "D65") return "the CIE 1 nm table (cie_d65_1nm.csv)";
  return "a constant (cie_e_5nm.csv)";
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path data, out;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--data") == 0) data = argv[i + 1];
    else if (std::strcmp(argv[i], "--out") == 0) out = argv[i + 1];
  }
  if (data.empty() || out.empty()) {
    std::cerr << "usage: rimu-e308-weights --data <data root> --out <folder>\n";
    return 1;
  }
  try {
    SpectralLibrary library(data);
    std::filesystem::create_directories(out);
    for (const std::string& name : SpectralLibrary::e308_illuminant_names()) {
      const SpectrumPtr illuminant = library.e308_illuminant(name);
      for (StandardObserver observer : {StandardObserver::cie1931_2deg, StandardObserver::cie1964_10deg}) {
        const Observer& o = library.observer(observer);
        const bool ten = observer == StandardObserver::cie1964_10deg;
        for (int interval : {10, 20}) {
          const E308WeightTable table6 = compute_e308_weights(*illuminant, o, interval, name);
          std::string lower = name;
          for (char& ch : lower) ch = char(std::tolower(static_cast<unsigned char>(ch)));
          const std::string stem = "astm_e308_" + lower + "_" + (ten ? "10" : "2") + "deg_" + std::to_string(interval) + "nm";
          const std::string what = "CIE " + name + ", " + o.name + ", " + std::to_string(interval) +
                                   " nm, 360-" + (interval == 20 ? "820" : "830") + " nm, sum of Wy = 100.\n"
                                   "Illuminant from " + source_of(name) + ".\n";
          const std::string command =
              "Generated from the CIE tables in data/ by: build/bin/rimu-e308-weights --data data --out data/e308";
          const std::string comment6 =
              "ASTM E308-15 Table 6 practice, for spectral data corrected for bandpass (E2022-11 Lagrange weights): " +
              what + command;
          const std::string comment5 =
              "ASTM E308-15 Table 5 practice, for spectral data NOT corrected for bandpass (triangular bandpass = "
              "interval): the Table 6 weights (" + stem + ".csv) with the Stearns & Stearns correction folded in, "
              "W5_i = 1.166 W6_i - 0.083 (W6_i-1 + W6_i+1), ends 1.083 W6_1 - 0.083 W6_2: " + what + command;
          const E308WeightTable table5 = e308_table5_from_table6(table6);
          for (const auto& [file, text] : {std::pair{out / (stem + ".csv"), e308_weights_csv(table6, comment6)},
                                           std::pair{out / (stem + "_table5.csv"), e308_weights_csv(table5, comment5)}}) {
            std::ofstream f(file);
            f << text;
            f.close();
            if (!f) {
              std::cerr << "rimu-e308-weights: cannot write " << file.string() << "\n";
              return 2;
            }
            std::cout << "wrote " << file.string() << "\n";
          }
        }
      }
    }
    return 0;
  } catch (const InputError& e) {
    std::cerr << "rimu-e308-weights: " << e.what() << "\n";
    return 1;
  }
}
