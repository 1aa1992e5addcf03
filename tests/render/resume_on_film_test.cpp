// --resume's set-up (resume_on_film, render/output/partial_exr.h): the film starts from the partial where the
// partial stopped, and a partial whose window or spectral bins are not the rebuilt film's is refused, naming its file.
#include <doctest/doctest.h>

#include <string>

#include "render/film/film.h"
#include "render/output/partial_exr.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;

namespace {

// A partial of samples [0, 24) over `crop` read as a header (no sums: add_partial_to_film adds nothing).
PartialImage header_partial(PixelBounds crop, int spectral_bins) {
  PartialImage partial;
  partial.path = "shot.0001.exr";
  partial.width = 16;
  partial.height = 8;
  partial.crop = crop;
  partial.spectral_bins = spectral_bins;
  partial.record.samples = {SampleRange{0, 24}};
  partial.record.requested = SampleRange{0, 64};
  partial.metadata.render_time_s = 12.5;
  return partial;
}

std::string message_of(const PartialImage& partial, Film& film) {
  try {
    resume_on_film(partial, film);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("resume_on_film continues after the partial's last sample and keeps its render time") {
  Film film(FilmOptions{16, 8, PixelBounds{2, 1, 10, 7}, 0}, SpectralResponse::cie_xyz(test::library()));
  const ResumePoint resume = resume_on_film(header_partial(PixelBounds{2, 1, 10, 7}, 0), film);
  CHECK(resume.first_sample == 24);
  CHECK(resume.render_time_s == 12.5);
}

TEST_CASE("resume_on_film refuses a partial whose window or spectral bins differ from the film's, naming the file") {
  Film film(FilmOptions{16, 8, PixelBounds{2, 1, 10, 7}, 4}, SpectralResponse::cie_xyz(test::library()));
  const std::string window = message_of(header_partial(PixelBounds{0, 0, 16, 8}, 4), film);
  CHECK(window.find("shot.0001.exr") != std::string::npos);
  CHECK(window.find("window or spectral bins differ") != std::string::npos);
  const std::string bins = message_of(header_partial(PixelBounds{2, 1, 10, 7}, 8), film);
  CHECK(bins.find("shot.0001.exr") != std::string::npos);
  CHECK(bins.find("window or spectral bins differ") != std::string::npos);
}
