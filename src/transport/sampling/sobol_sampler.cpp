#include "transport/sampling/sobol_sampler.h"

namespace rimu {
namespace {

// Salts of the nine key words of a draw (arbitrary distinct odd constants: each word hashes the draw's hash XOR
// its salt, so the words are as unrelated as hash32's outputs for different inputs).
constexpr uint32_t kWordSalt[9] = {0x9e3779b9u, 0x3c6ef372u, 0xdaa66d2bu, 0x78dde6e4u, 0x1715609du,
                                   0xb54cda56u, 0x5384540fu, 0xf1bbcdc8u, 0x8ff34781u};

// The hash of draw `draw` under pixel key (key0, key1): a Weyl step over the draws, hashed, then the second key
// word mixed in, so (pixel, draw) pairs differ in 64 bits of key even where 32-bit sums collide.
constexpr uint32_t draw_hash(uint32_t key0, uint32_t key1, uint32_t draw) {
  return hash32(key0 + (draw + 1u) * 0x9e3779b9u) ^ key1;
}

// One multiply-xorshift round is enough here: the input is already a full hash32 output (draw_hash), the round
// only has to make the nine salted copies unrelated (sobol_owen_test checks the resulting scrambles).
constexpr uint32_t key_word(uint32_t hash, int word) {
  const uint32_t x = (hash ^ kWordSalt[word]) * 0x7feb352du;
  return x ^ (x >> 16);  // the xorshift carries high bits down: low bits of a product see only low bits
}

// An AVX2 clone of the two batch loops, chosen at run time, is a GCC-only speed-up here: clang wants
// target_clones on the first declaration (these are member functions declared in the header, and used inline
// there), so a clang build (the fuzzing build, docs/fuzzing.md) keeps the one SSE4.1 version.
#if defined(__GNUC__) && !defined(__clang__)
#define RIMU_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RIMU_AVX2_CLONES
#endif

}  // namespace

DrawKeys sobol_draw_keys(uint32_t key0, uint32_t key1, uint32_t draw) {
  const uint32_t h = draw_hash(key0, key1, draw);
  return {{key_word(h, 0), key_word(h, 1), key_word(h, 2)},
          {key_word(h, 3), key_word(h, 4), key_word(h, 5)},
          {key_word(h, 6), key_word(h, 7), key_word(h, 8)}};
}

void SobolSampler::start_pixel_sample(int x, int y, uint32_t sample_index) {
  if (!has_pixel_ || x != pixel_x_ || y != pixel_y_) {
    // Per-pixel scrambling seeds (the pixel decorrelation): every pixel owns an independent Owen scramble and
    // shuffle of every draw; the seed enters hashed so that seeds 1, 2, 3 are as unrelated as any.
    const uint64_t pixel = (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
    const uint64_t key = mix_bits(pixel ^ mix_bits(seed_ + 0x632be59bd9b4e019ULL));
    pixel_key_[0] = uint32_t(key);
    pixel_key_[1] = uint32_t(key >> 32);
    pixel_x_ = x;
    pixel_y_ = y;
    has_pixel_ = true;
    cached_batches_ = 0;
  }
  reversed_index_ = reverse_bits(sample_index);
  draw_ = 0;
  dimension_ = 0;
  batch_first_draw_ = ~0u - kBatch;  // no batch yet: lane_of_next_draw() computes one
}

RIMU_AVX2_CLONES void SobolSampler::compute_key_words(
    const uint32_t pixel_key[2], uint32_t first_draw, uint32_t (&words)[9][kBatch]) {
  // The same formulas as sobol_draw_keys, lane by lane, in loops the compiler vectorises.
  uint32_t hash[kBatch];
  for (int lane = 0; lane < kBatch; ++lane) hash[lane] = draw_hash(pixel_key[0], pixel_key[1], first_draw + uint32_t(lane));
  for (int w = 0; w < 9; ++w)
    for (int lane = 0; lane < kBatch; ++lane) words[w][lane] = key_word(hash[lane], w);
}

RIMU_AVX2_CLONES void SobolSampler::compute_batch(uint32_t first_draw) {
  // Draws are consumed in order, so batches start at multiples of kBatch and batch b follows batch b − 1: the
  // words of batch b are either cached or about to be (b == cached_batches_), or b lies beyond the cache.
  const uint32_t batch = first_draw / uint32_t(kBatch);
  uint32_t uncached[9][kBatch];
  const uint32_t(*word)[kBatch] = uncached;
  if (batch < uint32_t(kCachedBatches)) {
    if (batch >= cached_batches_) {
      compute_key_words(pixel_key_, first_draw, key_words_[batch]);
      cached_batches_ = batch + 1;
    }
    word = key_words_[batch];
  } else {
    compute_key_words(pixel_key_, first_draw, uncached);
  }
  uint32_t u[kBatch], v[kBatch];
  for (int lane = 0; lane < kBatch; ++lane) {
    // In the bit-reversed domain where the scramble works: shuffle_index(i) = reverse(scramble(reverse(i))),
    // sobol_dimension0 = reverse, so u = reverse(scramble(i')), and dimension 1 comes out reversed directly.
    const uint32_t shuffled =
        reverse_bits(scramble_reversed_digits(reversed_index_, {word[0][lane], word[1][lane], word[2][lane]}));
    u[lane] = reverse_bits(scramble_reversed_digits(shuffled, {word[3][lane], word[4][lane], word[5][lane]}));
    v[lane] = reverse_bits(scramble_reversed_digits(sobol_dimension1_reversed(shuffled),
                                                    {word[6][lane], word[7][lane], word[8][lane]}));
  }
  for (int lane = 0; lane < kBatch; ++lane) {
    u_[lane] = bits_to_unit_float(u[lane]);
    v_[lane] = bits_to_unit_float(v[lane]);
  }
  batch_first_draw_ = first_draw;
}

}  // namespace rimu
