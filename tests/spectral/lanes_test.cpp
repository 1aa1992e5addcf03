// Float4 / Mask4 against a scalar reference, lane by lane.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "spectral/wavelengths/lanes.h"

using namespace rimu;

namespace {

// Bitwise equality, so that -0.0 vs 0.0 and NaN payloads count, and NaN == NaN.
bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

// Each operation: the lane-wise version and the scalar reference it must equal in every lane. SSE arithmetic
// is IEEE single precision with round-to-nearest, as scalar float arithmetic on x86-64, so results are
// bit-identical; min/max follow SSE's rule (the second operand when either is NaN), spelled out in the reference.
struct Add {
  static Float4 lanes(Float4 a, Float4 b) { return a + b; }
  static float scalar(float a, float b) { return a + b; }
};
struct Sub {
  static Float4 lanes(Float4 a, Float4 b) { return a - b; }
  static float scalar(float a, float b) { return a - b; }
};
struct Mul {
  static Float4 lanes(Float4 a, Float4 b) { return a * b; }
  static float scalar(float a, float b) { return a * b; }
};
struct Div {
  static Float4 lanes(Float4 a, Float4 b) { return a / b; }
  static float scalar(float a, float b) { return a / b; }
};
struct Min {
  static Float4 lanes(Float4 a, Float4 b) { return min(a, b); }
  static float scalar(float a, float b) { return a < b ? a : b; }
};
struct Max {
  static Float4 lanes(Float4 a, Float4 b) { return max(a, b); }
  static float scalar(float a, float b) { return a > b ? a : b; }
};
struct MulAdd {  // a·b + a: two roundings, as documented (no FMA)
  static Float4 lanes(Float4 a, Float4 b) { return mul_add(a, b, a); }
  static float scalar(float a, float b) {
    const volatile float product = a * b;  // volatile: keep the compiler from contracting into an FMA
    return product + a;
  }
};
struct Select {  // a < b ? a : b through select, with the comparison and the blend
  static Float4 lanes(Float4 a, Float4 b) { return select(a < b, a, b); }
  static float scalar(float a, float b) { return a < b ? a : b; }
};
struct Neg {  // unary, the second input ignored
  static Float4 lanes(Float4 a, Float4) { return -a; }
  static float scalar(float a, float) { return -a; }
};
struct Abs {
  static Float4 lanes(Float4 a, Float4) { return abs(a); }
  static float scalar(float a, float) { return std::fabs(a); }
};
struct Floor {
  static Float4 lanes(Float4 a, Float4) { return floor(a); }
  static float scalar(float a, float) { return std::floor(a); }
};
struct Sqrt {
  static Float4 lanes(Float4 a, Float4) { return sqrt(abs(a)); }
  static float scalar(float a, float) { return std::sqrt(std::fabs(a)); }
};

// Random floats over many magnitudes and both signs, plus a few specials.
float random_float(std::mt19937& rng) {
  std::uniform_real_distribution<float> mantissa(-2.0f, 2.0f);
  std::uniform_int_distribution<int> exponent(-30, 30);
  return std::ldexp(mantissa(rng), exponent(rng));
}

Float4 random_float4(std::mt19937& rng) {
  return Float4(random_float(rng), random_float(rng), random_float(rng), random_float(rng));
}

}  // namespace

TEST_CASE_TEMPLATE("lane-wise operations equal the scalar reference in every lane", Op, Add, Sub, Mul, Div, Min,
                   Max, MulAdd, Select, Neg, Abs, Floor, Sqrt) {
  std::mt19937 rng(12345);
  for (int i = 0; i < 2000; ++i) {
    const Float4 a = random_float4(rng), b = random_float4(rng);
    const Float4 r = Op::lanes(a, b);
    for (int lane = 0; lane < kLaneCount; ++lane) {
      if (!same_bits(r[lane], Op::scalar(a[lane], b[lane]))) {
        CAPTURE(a[lane]);
        CAPTURE(b[lane]);
        CHECK(r[lane] == Op::scalar(a[lane], b[lane]));
      }
    }
  }
}

TEST_CASE_TEMPLATE("lanes are independent: changing one input lane changes only that output lane", Op, Add, Sub,
                   Mul, Div, Min, Max, MulAdd, Select, Neg, Abs, Floor, Sqrt) {
  std::mt19937 rng(777);
  for (int i = 0; i < 500; ++i) {
    const Float4 a = random_float4(rng), b = random_float4(rng);
    const Float4 before = Op::lanes(a, b);
    for (int lane = 0; lane < kLaneCount; ++lane) {
      Float4 a2 = a, b2 = b;
      a2.set(lane, random_float(rng));
      b2.set(lane, random_float(rng));
      const Float4 after = Op::lanes(a2, b2);
      CHECK(same_bits(after[lane], Op::scalar(a2[lane], b2[lane])));
      for (int other = 0; other < kLaneCount; ++other)
        if (other != lane) CHECK(same_bits(after[other], before[other]));
    }
  }
}

TEST_CASE("comparisons follow IEEE rules per lane, NaN included") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float values[] = {-1.0f, 0.0f, -0.0f, 2.5f, nan, INFINITY, -INFINITY};
  for (const float x : values) {
    for (const float y : values) {
      const Float4 a(x, y, x, y), b(y, x, x, y);  // every ordering of (x, y) and each with itself
      for (int lane = 0; lane < kLaneCount; ++lane) {
        const float p = a[lane], q = b[lane];
        CHECK((a < b)[lane] == (p < q));
        CHECK((a <= b)[lane] == (p <= q));
        CHECK((a > b)[lane] == (p > q));
        CHECK((a >= b)[lane] == (p >= q));
        CHECK((a == b)[lane] == (p == q));
        CHECK((a != b)[lane] == (p != q));  // true for NaN, like the scalar operator
      }
    }
  }
}

TEST_CASE("mask logic, any/all/none and select over all 16 patterns") {
  auto mask_of = [](int bits) {
    return Float4(float(bits & 1), float((bits >> 1) & 1), float((bits >> 2) & 1), float((bits >> 3) & 1)) >
           Float4(0.5f);
  };
  for (int m = 0; m < 16; ++m) {
    const Mask4 a = mask_of(m);
    CHECK(a.bits() == m);
    CHECK(a.any() == (m != 0));
    CHECK(a.all() == (m == 15));
    CHECK(a.none() == (m == 0));
    CHECK((!a).bits() == (~m & 15));
    const Float4 chosen = select(a, Float4(1.0f, 2.0f, 3.0f, 4.0f), Float4(-1.0f, -2.0f, -3.0f, -4.0f));
    for (int lane = 0; lane < kLaneCount; ++lane) {
      CHECK(a[lane] == bool((m >> lane) & 1));
      CHECK(chosen[lane] == (a[lane] ? float(lane + 1) : -float(lane + 1)));
    }
    for (int n = 0; n < 16; ++n) {
      const Mask4 b = mask_of(n);
      CHECK((a & b).bits() == (m & n));
      CHECK((a | b).bits() == (m | n));
      CHECK((a ^ b).bits() == (m ^ n));
    }
  }
  CHECK(Mask4(true).all());
  CHECK(Mask4(false).none());
  CHECK(Mask4().none());
}

TEST_CASE("is_nan and is_finite with NaN, ±Inf, denormals and extremes") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float denormal = std::numeric_limits<float>::denorm_min();
  const float largest = std::numeric_limits<float>::max();
  REQUIRE(std::fpclassify(denormal) == FP_SUBNORMAL);
  struct Case {
    float x;
    bool nan, finite;
  };
  const Case cases[] = {{nan, true, false},       {-nan, true, false},        {INFINITY, false, false},
                        {-INFINITY, false, false}, {denormal, false, true},    {-denormal, false, true},
                        {0.0f, false, true},       {-0.0f, false, true},       {largest, false, true},
                        {-largest, false, true},   {1e-38f, false, true},      {std::sqrt(-1.0f), true, false}};
  for (const Case& c : cases) {
    CAPTURE(c.x);
    // Put the value in each lane in turn among ordinary numbers, so a lane mix-up shows.
    for (int lane = 0; lane < kLaneCount; ++lane) {
      Float4 v(1.0f, 2.0f, 3.0f, 4.0f);
      v.set(lane, c.x);
      CHECK(is_nan(v).bits() == (c.nan ? 1 << lane : 0));
      CHECK(is_finite(v).bits() == (c.finite ? 15 : 15 & ~(1 << lane)));
    }
  }
  // A denormal survives arithmetic (no flush-to-zero in the lane type's build).
  CHECK((Float4(denormal) * Float4(2.0f))[0] == 2.0f * denormal);
}

TEST_CASE("horizontal sum, min_lane, max_lane") {
  // Exactly representable sums are order-independent: those must be exact.
  CHECK(sum(Float4(1.0f, 2.0f, 3.0f, 4.0f)) == 10.0f);
  CHECK(sum(Float4(-0.5f, 0.25f, 1024.0f, -1024.0f)) == -0.25f);
  // Otherwise the order of the additions is not part of the contract, so compare with the error bound of any
  // order of three float additions: |error| ≤ 3 · 2⁻²⁴ · Σ|aᵢ| (Higham, "Accuracy and Stability of Numerical
  // Algorithms", 2nd ed., §4.2), against a double-precision reference.
  std::mt19937 rng(99);
  for (int i = 0; i < 5000; ++i) {
    const Float4 a = random_float4(rng);
    double exact = 0.0, magnitude = 0.0;
    for (int lane = 0; lane < kLaneCount; ++lane) {
      exact += a[lane];
      magnitude += std::fabs(a[lane]);
    }
    CHECK(std::abs(double(sum(a)) - exact) <= 3.0 * std::ldexp(1.0, -24) * magnitude);
    CHECK(max_lane(a) == std::fmax(std::fmax(a[0], a[1]), std::fmax(a[2], a[3])));
    CHECK(min_lane(a) == std::fmin(std::fmin(a[0], a[1]), std::fmin(a[2], a[3])));
  }
  CHECK(std::isnan(sum(Float4(1.0f, std::numeric_limits<float>::quiet_NaN(), 2.0f, 3.0f))));
  // min_lane and max_lane keep std::fmin/fmax's rule for NaN: NaN lanes are ignored, NaN only if all are.
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (int lane = 0; lane < kLaneCount; ++lane) {
    Float4 a(-3.0f, 5.0f, -7.0f, 2.0f);
    const float removed = a[lane];
    a.set(lane, nan);
    float largest = -inf, smallest = inf;
    for (int k = 0; k < kLaneCount; ++k)
      if (k != lane) largest = std::max(largest, a[k]), smallest = std::min(smallest, a[k]);
    CAPTURE(removed);
    CHECK(max_lane(a) == largest);
    CHECK(min_lane(a) == smallest);
  }
  CHECK(max_lane(Float4(nan, nan, -2.0f, nan)) == -2.0f);
  CHECK(min_lane(Float4(nan, 4.0f, nan, nan)) == 4.0f);
  CHECK(std::isnan(max_lane(Float4(nan))));
  CHECK(std::isnan(min_lane(Float4(nan))));
  CHECK(max_lane(Float4(-inf, nan, -inf, nan)) == -inf);
  CHECK(min_lane(Float4(inf, inf, nan, inf)) == inf);
  CHECK(max_lane(Float4(-inf, 1e-30f, -1e38f, 0.0f)) == 1e-30f);
  CHECK(min_lane(Float4(inf, -1e-30f, 1e38f, 0.0f)) == -1e-30f);
}

TEST_CASE("construction, load, set, to_array, exp") {
  const float data[] = {0.5f, -1.0f, 3.0f, 7.25f};
  const Float4 v = Float4::load(data);
  const auto array = v.to_array();
  for (int lane = 0; lane < kLaneCount; ++lane) {
    CHECK(v[lane] == data[lane]);
    CHECK(array[lane] == data[lane]);
    CHECK(Float4(2.0f)[lane] == 2.0f);  // broadcast
    CHECK(Float4()[lane] == 0.0f);
    CHECK(exp(v)[lane] == std::exp(data[lane]));
  }
  Float4 w = v;
  w.set(2, 42.0f);
  CHECK(w.to_array() == std::array<float, 4>{0.5f, -1.0f, 42.0f, 7.25f});
  CHECK(clamp(Float4(-1.0f, 0.5f, 2.0f, 1.0f), Float4(0.0f), Float4(1.0f)).to_array() ==
        std::array<float, 4>{0.0f, 0.5f, 1.0f, 1.0f});
}
