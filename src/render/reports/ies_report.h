// What `rimu-light inspect file.ies` prints and draws: the photometric summary of an IES LM-63 file (peak candela,
// total lumens integrated from the table, luminaire efficiency against the lamp lumens, beam and field angles,
// illuminance at a distance) and a polar candela plot.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "render/scene/ies_file.h"
#include "render/scene/inspect_point.h"

namespace rimu {

/// A text report of `ies`; the illuminance is on a surface facing the lamp at the point's distance and angle from
/// the axis in the C = 0° plane (E = I/d²). With the electrical power (else the file's input watts) the luminaire
/// efficacy. Throws InputError for an invalid point or a result that is not finite (nothing prints NaN or inf).
std::string inspect_ies_text(const IesPhotometry& ies, const InspectPoint& point);
/// The same numbers as a JSON object (keys carry their units).
nlohmann::json inspect_ies_json(const IesPhotometry& ies, const InspectPoint& point);

/// Draws the candela distribution in the C 0-180° and C 90-270° planes as a polar plot against γ (nadir down,
/// angles labelled) in cd/klm (cd for absolute photometry) to a PNG (render/output/plot_output.h), titled with the file's
/// name. Throws InputError if `png` cannot be written (checked first), RenderError if gnuplot is missing or fails.
void plot_ies_polar_png(const IesPhotometry& ies, const std::filesystem::path& png);

}  // namespace rimu
