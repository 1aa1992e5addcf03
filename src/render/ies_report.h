// What `rimu-light inspect file.ies` prints and draws: the photometric summary of an IES LM-63 file (peak candela,
// total lumens integrated from the table, luminaire efficiency against the lamp lumens, beam and field angles,
// illuminance at a distance) and a polar candela plot.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "render/ies_file.h"

namespace rimu {

/// A text report of `ies`; the illuminance is on a surface facing the lamp at `distance_m`, `angle_deg` from the
/// axis in the C = 0° plane (E = I/d²). With `electrical_w` (else the file's input watts) the luminaire efficacy.
std::string inspect_ies_text(const IesPhotometry& ies, double distance_m, double angle_deg,
                             std::optional<double> electrical_w);

/// Draws the candela distribution in the C 0-180° and C 90-270° planes as a polar plot against γ (nadir down,
/// angles labelled) in cd/klm (cd for absolute photometry) to a PNG (render/plot_output.h), titled with the file's
/// name. Throws InputError if `png` cannot be written (checked first), RenderError if gnuplot is missing or fails.
void plot_ies_polar_png(const IesPhotometry& ies, const std::filesystem::path& png);

}  // namespace rimu
