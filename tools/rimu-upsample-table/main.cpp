// rimu-upsample-table: computes the smoothest-spectrum tables of data/upsampling/ (see docs/upsampling.md).
//
//   rimu-upsample-table --data <data root> --out <folder> [--angles 144] [--radii 16]
//
// Exit codes (common/tool_main.h): 0 ok, 1 bad input (options, data files), 2 a failure (no QP solution, a write).
//
// For each white (upsampling_whites.h) and each polar grid point of its knot gamut, solves the smoothness QP
// (smoothest_spectrum.h) and stores the spectrum and its brightness limit (upsampling_table.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/tool_main.h"

#include "spectral/error.h"
#include "spectral/upsampling/smoothest_spectrum.h"
#include "spectral/upsampling/upsampling_table.h"
#include "spectral/upsampling/upsampling_whites.h"

using namespace rimu;

namespace {

UpsamplingTable make_table(SpectralLibrary& library, const UpsamplingWhite& white, int angles, int radii) {
  const TabulatedSpectrum illuminant = upsampling_illuminant(library, white);
  const KnotColorimetry colorimetry(library.observer(StandardObserver::cie1931_2deg), illuminant, white.white);
  const KnotGamut gamut(colorimetry);
  UpsamplingTable table;
  table.white_name = white.name;
  table.white = white.white;
  table.angle_count = angles;
  table.radius_count = radii;
  table.hull = gamut.vertices();
  table.luminance_limits.resize(size_t(angles) * radii);
  table.shapes.resize(table.luminance_limits.size() * kUpsampleKnotCount);
  int total_iterations = 0;
  for (int a = 0; a < angles; ++a) {
    const double angle = 2 * std::numbers::pi * a / angles;
    for (int r = 0; r < radii; ++r) {
      const size_t e = table.entry(a, r);
      KnotValues knots;
      if (r == 0) {
        knots.fill(1.0);  // the white's smoothest spectrum is flat: roughness 0 and, by construction, the white
      } else {
        const Chromaticity xy = gamut.at(angle, table.radius_of_row(r) * table.usable_fraction);
        const auto solution = smoothest_knot_spectrum(colorimetry, xyz_from_xyY(xy, 1.0));
        if (!solution) {
          char where[160];
          std::snprintf(where, sizeof where, "white %s angle %d radius %d (x %.6f, y %.6f)", white.name.c_str(), a, r,
                        xy.x, xy.y);
          throw std::runtime_error(std::string("the smoothness QP has no solution at ") + where);
        }
        knots = solution->knots;
        total_iterations += solution->iterations;
      }
      double peak = 0;
      for (double v : knots) peak = std::fmax(peak, v);
      for (double& v : knots) v /= peak;
      table.luminance_limits[e] = r == 0 ? 1.0f : float(colorimetry.xyz_of(knots).y);
      for (int i = 0; i < kUpsampleKnotCount; ++i)
        table.shapes[e * kUpsampleKnotCount + i] = uint16_t(std::lround(knots[i] * 65535.0));
    }
  }
  std::printf("white %s: %zu hull vertices, %d entries, mean %.1f active-set iterations\n", white.name.c_str(),
              table.hull.size(), angles * radii, double(total_iterations) / (angles * (radii - 1)));
  return table;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data, out;
  int angles = 144, radii = 16;
  return run_tool(
      {"rimu-upsample-table", "rimu-upsample-table: computes the smoothest-spectrum tables of data/upsampling/ "
                              "(docs/upsampling.md)"},
      argc, argv,
      [&](CLI::App& app) {
        app.add_option("--data", data, "the data root (the folder holding cmf/ and spectra/)")->required();
        app.add_option("--out", out, "the folder to write the tables to")->required();
        app.add_option("--angles", angles, "polar grid: angles per white (default 144)")->check(CLI::Range(3, 100000));
        app.add_option("--radii", radii, "polar grid: radii per angle (default 16)")->check(CLI::Range(2, 100000));
      },
      [&] {
        std::filesystem::create_directories(out);
        SpectralLibrary library(data);
        for (const UpsamplingWhite& white : upsampling_whites()) {
          const auto start = std::chrono::steady_clock::now();
          const UpsamplingTable table = make_table(library, white, angles, radii);
          const auto path = std::filesystem::path(out) / upsampling_table_file(white).filename();
          table.write(path);
          std::printf("  wrote %s in %.1f s\n", path.c_str(),
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
      });
}
