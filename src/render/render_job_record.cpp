// What a partial render records about its job: the scene hash and the options as JSON (render_job.h).
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "render/scene/json_cursor.h"
#include "render/render_job.h"

namespace rimu {
namespace {

// The options that change the image (not the samples, seed or crop: a merge checks those on their own).
nlohmann::json image_options(const RenderJob& job) {
  nlohmann::json j = nlohmann::json::object();
  if (job.width) j["width"] = *job.width;
  if (job.height) j["height"] = *job.height;
  if (job.sampler) j["sampler"] = sampler_kind_name(*job.sampler);
  if (job.wavelengths) j["wavelengths"] = wavelength_mode_name(*job.wavelengths);
  if (job.wavelength_density)
    j["wavelength_density"] = *job.wavelength_density == WavelengthDensityKind::lights ? "lights" : "visible";
  if (job.film) j["film"] = *job.film;
  if (job.iso) j["iso"] = *job.iso;
  if (job.shutter_s) j["shutter_s"] = *job.shutter_s;
  if (job.f_number) j["f_number"] = *job.f_number;
  if (job.compensation_ev) j["ev"] = *job.compensation_ev;
  if (job.white_balance) j["white_balance"] = *job.white_balance;
  if (job.frame) j["frame"] = *job.frame;
  if (job.light_sampler) j["light_sampler"] = light_sampler_kind_name(*job.light_sampler);
  if (job.guiding) j["guiding"] = *job.guiding;
  if (job.daylit_points) j["daylit_points"] = *job.daylit_points;
  if (job.caustics) j["caustics"] = *job.caustics;
  if (job.method) j["method"] = *job.method;
  if (job.max_sample_value) j["max_sample_value"] = *job.max_sample_value;
  if (job.strict) j["strict"] = true;
  return j;
}

// `path` relative to `folder` if inside it (no "..").
std::optional<std::string> relative_inside(const std::filesystem::path& path, const std::filesystem::path& folder) {
  std::error_code error;
  const std::filesystem::path base = std::filesystem::absolute(folder, error).lexically_normal();
  if (error) return std::nullopt;
  const std::filesystem::path relative = path.lexically_relative(base);
  if (relative.empty() || *relative.begin() == "..") return std::nullopt;
  return relative.generic_string();
}

// A file a library read itself (an image): its bytes, read in blocks (it may be hundreds of MB). A file that
// vanished since hashes as nothing; the next load reports it.
uint64_t hash_file_bytes(const std::filesystem::path& path) {
  uint64_t h = fnv1a("");
  std::ifstream in(path, std::ios::binary);
  std::vector<char> block(1 << 20);
  while (in) {
    in.read(block.data(), std::streamsize(block.size()));
    h = fnv1a(std::string_view(block.data(), size_t(in.gcount())), h);
  }
  return h;
}

}  // namespace

std::string scene_hash_of_files(const InputFileLog& files, const std::filesystem::path& scene_path,
                                const std::filesystem::path& data_root, const RenderJob& job) {
  // By name, so the order the readers happened to read in does not matter.
  std::map<std::string, uint64_t> named;
  const std::filesystem::path scene_folder = scene_path.parent_path().empty() ? "." : scene_path.parent_path();
  for (const auto& [path, digest] : files.files()) {
    std::string name;
    if (const auto in_scene = relative_inside(path, scene_folder)) name = *in_scene;
    else if (const auto in_data = relative_inside(path, data_root)) name = "data:" + *in_data;
    else name = path.generic_string();
    named[name] = digest ? *digest : hash_file_bytes(path);
  }
  uint64_t h = fnv1a("rimu scene hash 2");  // the files read, not the names a scene's strings hold (version 1)
  for (const auto& [name, digest] : named) {
    h = fnv1a(name + '\0', h);
    for (int byte = 0; byte < 8; ++byte) h = fnv1a(std::string(1, char((digest >> (8 * byte)) & 0xff)), h);
  }
  h = fnv1a(image_options(job).dump(), h);
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::string render_job_json(const RenderJob& job) {
  nlohmann::json j = image_options(job);
  if (job.scene) j["scene"] = std::filesystem::absolute(*job.scene).lexically_normal().string();
  if (job.samples_per_pixel) j["spp"] = *job.samples_per_pixel;
  if (job.seed) j["seed"] = std::to_string(*job.seed);
  if (job.crop) j["crop"] = {job.crop->x0, job.crop->y0, job.crop->x1, job.crop->y1};
  if (job.samples) j["samples"] = job.samples->text();
  if (job.checkpoint_interval_s) j["checkpoint_s"] = *job.checkpoint_interval_s;
  if (job.time_limit_s) j["time_limit_s"] = *job.time_limit_s;
  if (job.png_output) j["png"] = std::filesystem::absolute(*job.png_output).lexically_normal().string();
  // The sensors are measured after the image, so a resumed render measures them too: with the same options.
  if (job.sensors_output)
    j["sensors_out"] = std::filesystem::absolute(*job.sensors_output).lexically_normal().string();
  if (job.sensor_samples) j["sensor_samples"] = *job.sensor_samples;
  j["float"] = !job.half_exr;  // the key of the records written when half was the default
  j["exposure_ev"] = job.exposure_ev;
  j["view"] = job.view;
  return j.dump();
}

RenderJob render_job_from_json(const std::string& json, const std::string& where) {
  const nlohmann::json j = parse_json_text(json, where);
  RenderJob job;
  try {
    if (j.contains("scene")) job.scene = j["scene"].get<std::string>();
    if (j.contains("width")) job.width = j["width"].get<int>();
    if (j.contains("height")) job.height = j["height"].get<int>();
    if (j.contains("spp")) job.samples_per_pixel = j["spp"].get<int>();
    if (j.contains("seed")) job.seed = std::stoull(j["seed"].get<std::string>());
    if (j.contains("sampler")) job.sampler = parse_sampler_kind(j["sampler"].get<std::string>());
    if (j.contains("wavelengths")) job.wavelengths = parse_wavelength_mode(j["wavelengths"].get<std::string>());
    if (j.contains("wavelength_density"))
      job.wavelength_density = j["wavelength_density"] == "lights" ? WavelengthDensityKind::lights
                                                                   : WavelengthDensityKind::visible;
    if (j.contains("film")) job.film = j["film"].get<std::string>();
    if (j.contains("iso")) job.iso = j["iso"].get<double>();
    if (j.contains("shutter_s")) job.shutter_s = j["shutter_s"].get<double>();
    if (j.contains("f_number")) job.f_number = j["f_number"].get<double>();
    if (j.contains("ev")) job.compensation_ev = j["ev"].get<double>();
    if (j.contains("white_balance")) job.white_balance = j["white_balance"].get<std::string>();
    if (j.contains("frame")) job.frame = j["frame"].get<int>();
    if (j.contains("guiding")) job.guiding = j["guiding"].get<std::string>();
    if (j.contains("daylit_points")) job.daylit_points = j["daylit_points"].get<std::string>();
    if (j.contains("caustics")) job.caustics = j["caustics"].get<std::string>();
    if (j.contains("method")) job.method = j["method"].get<std::string>();
    if (j.contains("max_sample_value")) job.max_sample_value = j["max_sample_value"].get<double>();
    if (j.contains("crop")) {
      const auto& c = j["crop"];
      job.crop = PixelBounds{c[0].get<int>(), c[1].get<int>(), c[2].get<int>(), c[3].get<int>()};
    }
    if (j.contains("samples")) job.samples = parse_sample_range(j["samples"].get<std::string>(), where);
    if (j.contains("checkpoint_s")) job.checkpoint_interval_s = j["checkpoint_s"].get<double>();
    if (j.contains("time_limit_s")) job.time_limit_s = j["time_limit_s"].get<double>();
    if (j.contains("png")) job.png_output = j["png"].get<std::string>();
    if (j.contains("sensors_out")) job.sensors_output = j["sensors_out"].get<std::string>();
    if (j.contains("sensor_samples")) job.sensor_samples = j["sensor_samples"].get<int>();
    job.half_exr = !j.value("float", true);
    job.exposure_ev = j.value("exposure_ev", 0.0);
    job.view = j.value("view", std::string("Standard"));
  } catch (const nlohmann::json::exception& e) {
    throw InputError({where, 0, ""}, std::string("the recorded render job is malformed: ") + e.what());
  }
  return job;
}

}  // namespace rimu
