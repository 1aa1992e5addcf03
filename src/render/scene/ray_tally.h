// How many rays the calling thread has traced: every EmbreeScene::intersect and ::occluded call counts one.
//
// Why: the rays a pixel's samples trace are a deterministic measure of what the pixel costs (its paths' lengths,
// its shadow rays), which adaptive sampling weighs against the pixel's noise (render/film/adaptive_sampling.h).
// A clock would measure the same thing but differently on every run, and the sample counts it chose would make
// the image depend on the machine's load. One thread-local increment a ray: nothing next to the ray itself.
#pragma once

#include <cstdint>

namespace rimu {

namespace detail {
inline thread_local uint64_t rays_traced_by_thread = 0;
}  // namespace detail

/// Counts one traced ray on the calling thread.
inline void tally_traced_ray() { ++detail::rays_traced_by_thread; }

/// The rays the calling thread has traced since it started: differences between two calls are what ran between them.
inline uint64_t rays_traced_by_this_thread() { return detail::rays_traced_by_thread; }

}  // namespace rimu
