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

/// A text report of `ies`, its candela scaled to `luminaire_lumens` in all when given (rimu-light inspect --lumens,
/// an authored definition's luminous_power_lm): the peak, the intensities in the C 0°, 90°, 180° and 270° planes
/// every 10° of γ, the illuminance on the axis at 1, 2 and 3 m, beam and field angles; the illuminance is on a surface facing the lamp at the point's distance and angle from
/// the axis in the C = 0° plane (E = I/d²). With the electrical power (else the file's input watts) the luminaire
/// efficacy. Throws InputError for an invalid point or a result that is not finite (nothing prints NaN or inf).
std::string inspect_ies_text(const IesPhotometry& ies, const InspectPoint& point,
                             std::optional<double> luminaire_lumens = {});
/// The same numbers as a JSON object (keys carry their units).
nlohmann::json inspect_ies_json(const IesPhotometry& ies, const InspectPoint& point,
                                std::optional<double> luminaire_lumens = {});

/// The γ angles of the plane table (0-180° every 10°, as far as the file's table reaches) and the distances of the
/// on-axis illuminance (1, 2, 3 m).
inline constexpr double kPlaneTableStepDeg = 10.0;
inline constexpr double kOnAxisDistancesM[] = {1.0, 2.0, 3.0};

/// Draws the candela distribution in the C 0-180° and C 90-270° planes as a polar plot against γ (nadir down,
/// angles labelled) in cd/klm (cd for absolute photometry) to a PNG (render/output/plot_output.h), titled with the file's
/// name; scaled to `luminaire_lumens` (then in cd) when given. Throws InputError at `option` if `png` cannot be
/// written (checked first), RenderError if gnuplot is missing or fails.
void plot_ies_polar_png(const IesPhotometry& ies, const std::filesystem::path& png,
                        std::optional<double> luminaire_lumens = {}, const std::string& option = "--plot-polar");

}  // namespace rimu
