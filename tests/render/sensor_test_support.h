// What the sensor tests share (render/sensors/sensor_measurement.h): a small scene around the sensors, loading it as
// a render job does, measuring it with a fixed seed, and the check of a reading against its exact value.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"
#include "test_support.h"

namespace rimu::test {

/// |reading − reference| ≤ 4.5 standard errors. A reading's standard error comes from 16 independent replicates
/// (replicates_for), so a correct estimator's error over it has a t distribution of 15 degrees of freedom: the check
/// fails with probability 4.2e-4 (fixed seeds make each outcome repeatable).
inline constexpr double kSensorSigmas = 4.5;

/// A z-up scene with a grey (ρ = 0.5) and a black diffuse material, its lights, shapes and "sensors" section.
inline nlohmann::json sensor_scene(nlohmann::json lights, nlohmann::json sensors,
                                   nlohmann::json shapes = nlohmann::json::array()) {
  return {{"camera", {{"from", {0, -5, 1}}, {"to", {0, 0, 0}}, {"up", {0, 0, 1}}}},
          {"materials", {{"grey", {{"type", "diffuse"}, {"reflectance", 0.5}}},
                         {"black", {{"type", "diffuse"}, {"reflectance", 0.0}}}}},
          {"lights", std::move(lights)},
          {"shapes", std::move(shapes)},
          {"sensors", std::move(sensors)}};
}

/// A scene and its sensors, read as a render job reads them (load_scene checks the section; scene_sensors reads it).
struct LoadedSensors {
  std::unique_ptr<Scene> scene;
  SensorSettings sensors;
};

inline LoadedSensors load_sensors(const nlohmann::json& document, const std::string& file_name,
                                  const std::filesystem::path& directory = std::filesystem::current_path()) {
  return {load_scene(document, file_name, directory, library()), scene_sensors(document, file_name)};
}

/// The sensors' readings at the section's sample count and replicates, with `seed`.
inline SensorReadings measure(const LoadedSensors& loaded, uint64_t seed) {
  SensorMeasureOptions options;
  options.samples = loaded.sensors.samples;
  options.replicates = loaded.sensors.replicates;
  options.seed = seed;
  return measure_sensors(*loaded.scene, loaded.sensors, library().photopic_v(), options);
}

/// The reading's standard error is small enough to tell a `max_relative_error` mistake apart, and the reading lies
/// within kSensorSigmas standard errors of the exact value.
inline void check_sensor_reading(const MeterReading& r, double expected, double max_relative_error = 0.02) {
  CAPTURE(r.value);
  CAPTURE(r.standard_error);
  CAPTURE(expected);
  CHECK(r.standard_error < max_relative_error * expected);
  CHECK(std::abs(r.value - expected) <= kSensorSigmas * r.standard_error);
}

}  // namespace rimu::test
