// libFuzzer target: the spectrum CSV reader (CsvTable) and the tabulated spectra built from its columns.
#include <algorithm>

#include "fuzz_support.h"
#include "spectral/io/csv_table.h"
#include "spectral/spectra/tabulated_spectrum.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_csv", [&] {
    const rimu::CsvTable table = rimu::CsvTable::parse(rimu::fuzz::as_text(data, size), "fuzz.csv");
    // Every column a spectrum could be read from (the first is the wavelength), as the scene loader and the
    // tools read them; bounded so one wide header does not dominate the run.
    for (size_t column = 1; column < std::min<size_t>(table.column_count(), 8); ++column) {
      for (const auto extrapolation : {rimu::Extrapolation::zero, rimu::Extrapolation::clamp}) {
        try {
          const auto spectrum = rimu::TabulatedSpectrum::from_csv(table, table.header()[column], extrapolation);
          for (double lambda_nm : {300.0, 360.0, 555.5, 830.0, 1000.0}) (void)spectrum.value(lambda_nm);
        } catch (const rimu::InputError&) {
        }
      }
    }
  });
}
