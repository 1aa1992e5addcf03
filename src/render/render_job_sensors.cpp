// The render job's sensor stages (declared in render_job_stages.h): the scene's "sensors" measured after the image
// with the same integrator, seed and sampler, or alone with --sensors-only.
#include <algorithm>
#include <ostream>
#include <vector>

#include "render/interrupt_flag.h"
#include "render/render_job_stages.h"
#include "render/sensors/sensor_measurement.h"
#include "render/sensors/sensor_outputs.h"
#include "render/sensors/sensor_plan.h"
#include "spectral/error.h"
#include "spectral/io/output_file.h"

namespace rimu {
namespace {

std::filesystem::path job_sensor_base(const RenderJob& job) {
  return job.sensors_output ? *job.sensors_output : default_sensor_output_base(job.exr_output);
}

SensorOutputPaths job_sensor_paths(const RenderJob& job) { return sensor_output_paths(job_sensor_base(job)); }

// Each grid's false-colour plan (gnuplot); without gnuplot the tables are still written, with a warning.
std::vector<std::filesystem::path> write_plans(const RenderJobState& s, const SensorReadings& readings) {
  std::vector<std::filesystem::path> written;
  const SensorSettings& sensors = s.sensors;
  // Photopic lux always; scotopic lux and melanopic EDI as well when the section asks for them.
  std::vector<PlanQuantity> quantities = {PlanQuantity::photopic};
  if (sensors.quantities.scotopic) quantities.push_back(PlanQuantity::scotopic);
  if (sensors.quantities.melanopic) quantities.push_back(PlanQuantity::melanopic_edi);
  for (size_t g = 0; g < sensors.grids.size(); ++g)
    for (const PlanQuantity quantity : quantities) {
      const std::filesystem::path png = grid_plan_path(job_sensor_base(s.job), sensors.grids[g], quantity);
      try {
        check_plot_destination(png, {png.string(), 0, "--sensors-out"});
      } catch (const PlotError& e) {
        s.log << "rimu: warning: no false-colour plans of the sensor grids: " << e.what() << "\n";
        return written;
      }
      write_grid_plan(png, sensors.grids[g], readings.grids[g], quantity);
      written.push_back(png);
    }
  return written;
}

}  // namespace

void check_job_sensors(RenderJobState& s) {
  const Scene& scene = *s.loaded.scene;
  s.sensors = scene_sensors(s.loaded.document, s.scene_path.string());
  if (s.sensors.empty()) {
    if (s.job.sensors_only)
      throw InputError({s.scene_path.string(), 0, "--sensors-only"},
                       "the scene has no \"sensors\" to measure (docs/scene-format.md, \"Sensors\")");
    return;
  }
  check_sensor_scene(scene, s.scene_path.string());
  check_daylight_factor_grids(scene, s.sensors, s.library.photopic_v(), s.scene_path.string());
  const SensorOutputPaths paths = job_sensor_paths(s.job);
  for (const std::filesystem::path& path : {paths.csv, paths.json}) {
    check_output_path(path);
    for (const std::filesystem::path& input : s.loaded.files_read)
      if (same_output_file(path, input))
        throw InputError({path.string(), 0, "--sensors-out"}, "is one of the scene's files (" + input.string() +
                                                                   "): choose another name");
    if (same_output_file(path, s.job.exr_output))
      throw InputError({path.string(), 0, "--sensors-out"}, "is the EXR output (-o): choose another name");
  }
}

void measure_job_sensors(RenderJobState& s, InterruptFlag& interrupt) {
  const Scene& scene = *s.loaded.scene;
  const SensorSettings& sensors = s.sensors;
  if (sensors.empty()) return;
  const RenderJob& job = s.job;
  if (!job.sensors_only && (job.samples || s.result.statistics.interrupted)) {
    if (!job.quiet)
      s.log << "rimu: sensors not measured: " << (job.samples ? "a --samples partial" : "the render was interrupted")
            << " (measure them with --sensors-only)\n";
    return;
  }
  SensorMeasureOptions options;
  options.samples = job.sensor_samples.value_or(sensors.samples);
  options.replicates = sensors.replicates;
  options.seed = scene.settings.seed;
  options.sampler = scene.settings.sampler;
  options.threads = job.threads.value_or(0);
  options.stop_requested = [&interrupt] { return interrupt.requested(); };
  if (sensors.quantities.scotopic) options.scotopic_v_prime = &s.library.scotopic_v_prime();
  if (sensors.quantities.melanopic) options.melanopic = &s.library.melanopic_action_spectrum();
  const SensorReadings readings = measure_sensors(scene, sensors, s.library.photopic_v(), options);
  if (readings.interrupted) {
    s.log << "rimu: sensors interrupted: nothing written\n";
    return;
  }
  const SensorOutputPaths paths = job_sensor_paths(job);
  write_sensor_outputs(paths, sensors, readings, options.samples);
  const std::vector<std::filesystem::path> plans = write_plans(s, readings);
  if (job.quiet) return;
  for (size_t g = 0; g < sensors.grids.size(); ++g) {
    const IlluminanceGrid& grid = sensors.grids[g];
    const GridReadings& r = readings.grids[g];
    double largest_error = 0.0;
    for (const MeterReading& m : r.points) largest_error = std::max(largest_error, m.standard_error);
    s.log << "rimu: sensor " << grid.name << " (" << grid.count_u << "x" << grid.count_v << "): Emin " << r.e_min_lx
          << " lx, Eavg " << r.e_avg_lx << " lx, Emax " << r.e_max_lx << " lx, U0 " << r.u0
          << "; largest standard error " << largest_error << " lx\n";
    if (const auto& df = r.daylight_factor)
      s.log << "rimu: sensor " << grid.name << ": daylight factor min " << df->df_min_percent << " %, avg "
            << df->df_avg_percent << " %, max " << df->df_max_percent << " % (E_out " << df->outdoor_illuminance_lx
            << " lx, CIE overcast sky)\n";
  }
  for (size_t k = 0; k < sensors.points.size(); ++k) {
    const PointSensor& p = sensors.points[k];
    const char* unit = p.kind == PointSensor::Kind::luminance ? " nt" : " lx";
    s.log << "rimu: sensor " << p.name << ": " << readings.meters[k].value
          << unit << " ± " << readings.meters[k].standard_error << unit << " (standard error)";
    if (k < readings.meters_scotopic.size())
      s.log << "; scotopic " << readings.meters_scotopic[k].value << unit << " ± "
            << readings.meters_scotopic[k].standard_error;
    if (k < readings.meters_melanopic.size())
      s.log << "; melanopic " << (p.kind == PointSensor::Kind::luminance ? "EDL " : "EDI ")
            << readings.meters_melanopic[k].value << unit << " ± " << readings.meters_melanopic[k].standard_error;
    s.log << "\n";
  }
  s.log << "rimu: sensors: " << options.samples << " samples per point in " << readings.seconds << " s";
  if (readings.discarded_samples) s.log << ", " << readings.discarded_samples << " discarded (NaN, Inf, negative)";
  s.log << "; wrote " << paths.csv.string() << ", " << paths.json.string();
  for (const std::filesystem::path& png : plans) s.log << ", " << png.string();
  s.log << "\n";
}

}  // namespace rimu
