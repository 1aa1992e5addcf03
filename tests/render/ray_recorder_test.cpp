// RecordingRayQueries counts and records exactly the queries made through it, answers them exactly as the
// geometry it wraps does (a render through it is bit-identical), and a replay traces the same rays.
#include <doctest/doctest.h>

#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "render/film/film.h"
#include "render/film/pixel_filter.h"
#include "render/reports/ray_recorder.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "test_support.h"

using namespace rimu;

namespace {

// The plane z = plane_z_m, seen from either side: a ray hits it iff its t = (z − o.z)/d.z lies in [t_min, t_max].
class PlaneQueries final : public RayQueries {
 public:
  explicit PlaneQueries(float plane_z_m) : plane_z_m_(plane_z_m) {}
  std::optional<SurfaceHit> intersect(const Ray& ray) const override {
    const float t = (plane_z_m_ - ray.origin.z) / ray.direction.z;
    if (!(t >= ray.t_min && t <= ray.t_max)) return std::nullopt;
    SurfaceHit hit;
    hit.t = t;
    hit.position = ray.origin + ray.direction * t;
    hit.geometric_normal = hit.shading_normal = {0, 0, 1};
    return hit;
  }
  bool occluded(const Ray& ray) const override { return intersect(ray).has_value(); }

 private:
  float plane_z_m_;
};

// Ray i from the origin: straight up (+z) unless i % 3 == 0 (down), with t_max = 0.5 (i % 4): 0, 0.5, 1, 1.5.
Ray test_ray(int i) {
  Ray r;
  r.origin = {0, 0, 0};
  r.direction = {0, 0, i % 3 == 0 ? -1.0f : 1.0f};
  r.t_max = 0.5f * float(i % 4);
  return r;
}

// Exact hit count of the rays [0, n) against the plane z = plane_z_m > 0: the upward rays whose t_max reaches it.
int expected_hits(int n, float plane_z_m) {
  int hits = 0;
  for (int i = 0; i < n; ++i) hits += i % 3 != 0 && 0.5f * float(i % 4) >= plane_z_m;
  return hits;
}

}  // namespace

TEST_CASE("RecordingRayQueries counts every query from many threads and answers as the geometry does") {
  constexpr int kRays = 20000;
  const PlaneQueries plane(1.0f);
  RecordingRayQueries counter(plane, RecordingRayQueries::Mode::count);
  std::vector<char> answer_differs(kRays, 0);
  // Even i: intersect, odd i: occluded; each compared with the undecorated plane's answer.
  tbb::parallel_for(0, kRays, [&](int i) {
    const Ray r = test_ray(i);
    if (i % 2 == 0) {
      const auto a = counter.intersect(r), b = plane.intersect(r);
      answer_differs[size_t(i)] = a.has_value() != b.has_value() || (a && a->t != b->t);
    } else {
      answer_differs[size_t(i)] = counter.occluded(r) != plane.occluded(r);
    }
  });
  int differing = 0;
  for (char d : answer_differs) differing += d;
  CHECK(differing == 0);

  int even_hits = 0, odd_hits = 0;
  for (int i = 0; i < kRays; ++i) (i % 2 == 0 ? even_hits : odd_hits) += i % 3 != 0 && i % 4 >= 2;
  CHECK(even_hits + odd_hits == expected_hits(kRays, 1.0f));
  const RayCounts counts = counter.counts();
  CHECK(counts.intersect == kRays / 2);
  CHECK(counts.occluded == kRays / 2);
  CHECK(counts.intersect_hits == uint64_t(even_hits));
  CHECK(counts.occluded_hits == uint64_t(odd_hits));
  CHECK(counter.take_recording().empty());  // count mode keeps no rays

  counter.reset();
  CHECK(counter.counts().total() == 0);
}

TEST_CASE("Recorded rays replay with the same answers through the same geometry, and not through another") {
  constexpr int kRays = 30000;
  const PlaneQueries plane(1.0f);
  RecordingRayQueries recorder(plane, RecordingRayQueries::Mode::record);
  tbb::parallel_for(0, kRays, [&](int i) {
    if (i % 2 == 0) recorder.intersect(test_ray(i));
    else recorder.occluded(test_ray(i));
  });
  const auto recording = recorder.take_recording();
  size_t recorded = 0;
  for (const auto& buffer : recording) recorded += buffer.size();
  CHECK(recorded == size_t(kRays));
  CHECK(recorder.take_recording().empty());  // taken, not copied

  const ReplayResult same = replay_rays(plane, recording);
  CHECK(same.rays == uint64_t(kRays));
  CHECK(same.mismatches == 0);
  CHECK(same.seconds > 0);

  // Moving the plane to z = 1.25 turns exactly the upward rays with t_max = 1 from hits into misses.
  const ReplayResult moved = replay_rays(PlaneQueries(1.25f), recording);
  CHECK(moved.mismatches == uint64_t(expected_hits(kRays, 1.0f) - expected_hits(kRays, 1.25f)));
  CHECK(moved.mismatches > 0);
}

TEST_CASE("A Cornell box render through RecordingRayQueries is bit-identical to the plain render") {
  SpectralLibrary& library = test::library();
  std::unique_ptr<Scene> scene = load_scene(default_scene_path(library), library);
  scene->settings.width = scene->settings.height = 16;
  const PixelFilter filter = PixelFilter::gaussian(scene->settings.filter.radius_px, scene->settings.filter.sigma_px);
  RenderOptions options;
  options.samples_per_pixel = 2;
  options.threads = 2;

  Film plain(FilmOptions{16, 16, std::nullopt, 0}, SpectralResponse::from_spec(library, "xyz"));
  render(*scene, filter, plain, options);

  RecordingRayQueries recorder(scene->geometry, RecordingRayQueries::Mode::record);
  TransportScene view = scene->transport_view();
  view.geometry = &recorder;
  Film counted(FilmOptions{16, 16, std::nullopt, 0}, SpectralResponse::from_spec(library, "xyz"));
  render(view, scene->settings.integrator, Camera(scene->camera, 16, 16), filter, counted, options);

  int differing_pixels = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) differing_pixels += plain.pixel_value(x, y) != counted.pixel_value(x, y);
  CHECK(differing_pixels == 0);
  // Every camera sample traces at least its primary ray.
  const RayCounts counts = recorder.counts();
  CHECK(counts.intersect >= 16u * 16u * 2u);
  CHECK(replay_rays(scene->geometry, recorder.take_recording()).mismatches == 0);
}
