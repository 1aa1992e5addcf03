#include "render/render_job.h"

#include <cstdio>
#include <ostream>
#include <sstream>

#include "render/interrupt_flag.h"
#include "render/output/partial_exr.h"
#include "render/render_job_stages.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene_frame.h"
#include "spectral/error.h"
#include "spectral/io/csv_table.h"

namespace rimu {

std::pair<int, int> parse_resolution(const std::string& text, const std::string& option) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
      w > 32768 || h > 32768)
    throw InputError({"", 0, option}, "expected WIDTHxHEIGHT with both in 1-32768, e.g. 640x480; got '" + text + "'");
  return {w, h};
}

PixelBounds parse_crop(const std::string& text, const std::string& option) {
  PixelBounds b{};
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &b.x0, &b.y0, &b.x1, &b.y1, &extra) != 4 || b.x0 < 0 || b.y0 < 0 ||
      b.x1 <= b.x0 || b.y1 <= b.y0)
    throw InputError({"", 0, option}, "expected x0,y0,x1,y1 (pixels, end exclusive, x1 > x0, y1 > y0); got '" + text + "'");
  return b;
}

double parse_max_sample_value(const std::string& text, const std::string& option) {
  double value = 0.0;
  if (!parse_finite_number(text, value) || !Film::valid_sample_clamp(value))
    throw InputError({"", 0, option}, std::string("expected the largest channel value a camera sample may keep, a "
                                                  "number from ") + Film::sample_clamp_range() +
                                          " in the written image's units (e.g. 20); got '" + text + "'");
  return value;
}

nlohmann::json read_pbrt_scene(const std::filesystem::path& path, SpectralLibrary& library, bool strict, std::ostream& log,
                               std::vector<PbrtOrigin>* origins) {
  PbrtImport imported = import_pbrt(path, library, {strict, {}});
  log << describe_ignored(imported.ignored);
  if (origins) *origins = std::move(imported.origins);
  return std::move(imported.document);
}

namespace {

// One render, from the scene file to the EXR: each stage is a function of render_job_stages.h, handing on what it
// made in RenderJobState. `previous`: a partial (checkpoint) of this job whose sums the film starts from; the
// render continues after its last sample.
RenderJobResult render_job(const RenderJob& job, const PartialImage* previous, InterruptFlag& interrupt,
                           std::ostream& log) {
  const DisplayOptions display = check_job_without_scene(job);
  RenderJobState state(job, previous, display, log);
  read_job_scene(state);
  check_job_sensors(state);
  if (!job.sensors_only) {
    set_up_film(state);
    plan_samples(state);
    render_samples(state, interrupt);
    write_job_outputs(state);
    log_job_summary(state);
  }
  measure_job_sensors(state, interrupt);
  return state.result;
}

// --resume: the recorded job, continued from the file's sums.
RenderJobResult resume_render_job(const RenderJob& job, InterruptFlag& interrupt, std::ostream& log) {
  const PartialImage previous = read_partial_exr(*job.resume);
  RenderJob resumed = render_job_from_json(previous.record.job, job.resume->string() + ": rimu:partial:job");
  resumed.threads = job.threads;
  resumed.quiet = job.quiet;
  resumed.exr_output = job.exr_output;
  if (job.checkpoint_interval_s) resumed.checkpoint_interval_s = job.checkpoint_interval_s;
  resumed.preview_output = job.preview_output;
  resumed.preview_interval_s = job.preview_interval_s;
  if (job.sensors_output) resumed.sensors_output = job.sensors_output;
  if (job.sensor_samples) resumed.sensor_samples = job.sensor_samples;
  const SampleRange requested = previous.record.requested;
  const std::vector<SampleRange>& held = previous.record.samples;
  if (held.size() > 1 || (held.size() == 1 && held.front().begin != requested.begin))
    throw InputError({job.resume->string(), 0, "--resume"},
                     "holds samples " + sample_ranges_text(held) + ", not one range starting at " +
                         std::to_string(requested.begin) + " (a merge of partials): render the missing samples with "
                         "--samples and merge them instead");
  if (held.empty()) return render_job(resumed, nullptr, interrupt, log);
  if (held.front().end >= requested.end) {
    if (!job.quiet) log << "rimu: " << job.resume->string() << " already holds samples " << requested.text()
        << ": nothing to resume\n";
    return {};
  }
  return render_job(resumed, &previous, interrupt, log);
}

}  // namespace

std::string scene_hash(const RenderJob& job) {
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const std::filesystem::path scene_path = job.scene ? *job.scene : default_scene_path(library);
  std::ostringstream ignored_report;  // the import's report of what it ignores: printed by the render, not here
  return load_job_scene(job, scene_path, library, ignored_report).hash;
}

RenderJobResult run_render_job(const RenderJob& job_in, std::ostream& log) {
  // Ctrl-C and SIGTERM are caught from here on, before anything slow (reading the scene, building the BVH): a
  // signal while the scene loads stops the render before its first sample, and the output is still written (0
  // samples; a checkpoint then resumes from the start). Before this line (process start, ~10 ms) it kills.
  InterruptFlag interrupt;
  RenderJob job = job_in;
  // "${frame}" in the output names, as in the scene (render/scene/scene_frame.h).
  job.exr_output = substitute_frame(job.exr_output.string(), job.frame, "-o");
  if (job.png_output) job.png_output = substitute_frame(job.png_output->string(), job.frame, "--png");
  if (job.preview_output) job.preview_output = substitute_frame(job.preview_output->string(), job.frame, "--preview");
  if (job.resume) return resume_render_job(job, interrupt, log);
  return render_job(job, nullptr, interrupt, log);
}

}  // namespace rimu
