// The false-colour plan of an illuminance grid: each cell coloured by its lux on a colour scale with a legend in lx,
// isolux contours over it, and the grid's Emin, Eavg, Emax and U0 in the title. Drawn by gnuplot
// (spectral/io/gnuplot_process.h: no shell, private folder, atomic install), as every plot of Rimu's.
#pragma once

#include <filesystem>

#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"
#include "spectral/io/gnuplot_process.h"

namespace rimu {

/// What a plan shows: a grid's photopic lux, its scotopic lux or its melanopic EDI (SensorSettings::quantities).
enum class PlanQuantity { photopic, scotopic, melanopic_edi };

/// The gnuplot job that draws `grid`'s plan of `quantity` (axes: metres along u and v from the grid's origin; the
/// title's minimum, average, maximum and U0 are of that quantity). `readings` must hold the quantity's points.
GnuplotJob grid_plan_job(const IlluminanceGrid& grid, const GridReadings& readings,
                         PlanQuantity quantity = PlanQuantity::photopic);

/// Draws it to `png` (RenderError if gnuplot fails; InputError if `png` cannot be written).
void write_grid_plan(const std::filesystem::path& png, const IlluminanceGrid& grid, const GridReadings& readings,
                     PlanQuantity quantity = PlanQuantity::photopic);

/// The plan's name for a grid: "base.<grid name>.png", "base.<grid name>.scotopic.png" or
/// "base.<grid name>.melanopic_edi.png".
std::filesystem::path grid_plan_path(const std::filesystem::path& base, const IlluminanceGrid& grid,
                                     PlanQuantity quantity = PlanQuantity::photopic);

}  // namespace rimu
