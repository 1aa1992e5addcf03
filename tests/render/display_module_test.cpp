// OpenColorIO is loaded on first use (render/output/display_module/display_module_api.h): a render that writes
// only an EXR never loads it, one that writes a PNG does, and a view given on an EXR-only render is still checked
// (the job records it for a later merge or resume).
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>

#include "image_module_test_support.h"
#include "input_error_check.h"
#include "render/output/display_transform.h"
#include "render/render_job.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

TEST_CASE("display module: a render that writes only an EXR does not load OpenColorIO, one with a PNG does") {
  if (test::reran_alone_if(display_library_loaded(), "display module: a render that writes only an EXR*")) return;
  test::ScratchFolder dir("display_module");
  std::ostringstream log;
  RenderJob job = test::tiny_render_job(dir / "only.exr");
  run_render_job(job, log);
  CHECK(fs::exists(dir / "only.exr"));
  CHECK_FALSE(display_library_loaded());
  // The check itself works: a PNG needs the display transform.
  job.exr_output = dir / "with.exr";
  job.png_output = dir / "with.png";
  run_render_job(job, log);
  CHECK(fs::exists(dir / "with.png"));
  CHECK(display_library_loaded());
}

TEST_CASE("display module: an unknown view is refused before rendering, with or without a PNG") {
  test::ScratchFolder dir("display_module_view");
  std::ostringstream log;
  RenderJob job = test::tiny_render_job(dir / "out.exr");
  job.view = "Filmic";
  test::input_error([&] { run_render_job(job, log); }, {"--view", "unknown view 'Filmic'", "Standard"});
  CHECK_FALSE(fs::exists(dir / "out.exr"));
  job.png_output = dir / "out.png";
  test::input_error([&] { run_render_job(job, log); }, {"--view", "unknown view 'Filmic'"});
  CHECK_FALSE(fs::exists(dir / "out.png"));
}
