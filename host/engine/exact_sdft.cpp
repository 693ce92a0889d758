#include "host/engine/exact_sdft.h"

#include <array>
#include <cmath>
#include <type_traits>
#include <utility>
#include <stdexcept>

#include "hls/carrier_magnitude.h"
#include "hls/sdft_bank.h"

namespace eskin::engine {
namespace {

constexpr int kLanes = 8;  // carrier padding: one AVX2 vector of int32

std::string field(const char* name, int v, const std::string& expected) {
  return std::string("sdft.") + name + ": expected " + expected + ", got " + std::to_string(v);
}

// The bank's arrays for the hot loop (restrict: nothing aliases).
struct Arrays {
  int kp, k;
  const uint32_t* __restrict inc;
  uint32_t* __restrict phase;
  int32_t* __restrict re;
  int32_t* __restrict im;
  int32_t* __restrict ring_re;
  int32_t* __restrict ring_im;
  const int32_t* __restrict packed;
  const int32_t* __restrict cos_t;
  const int32_t* __restrict nsin_t;
  int idx_shift, sh, xs;
  uint32_t idx_mask;
  size_t n;  // window
};

struct MagCtx {
  bool fast = false;
  MagnitudeWidths mw;
  double scale = 0;
  int32_t mag_max = 0;
};

MagCtx make_mag_ctx(const MagnitudeWidths& mw) {
  return MagCtx{magnitude_fast_ok(mw), mw,
                mw.shift == 0 ? 4.0 : std::ldexp(1.0, -(2 * mw.shift - 2)),
                (int32_t(1) << mw.mag_w) - 1};
}

// carrier_magnitude in double, exact when m.fast (see magnitude_fast_ok):
// Q = floor(P / 4^(SHIFT-1)) (4P for SHIFT 0), root = floor(sqrt(Q)) (the
// truncating conversion of a non-negative double is its floor), mag =
// (root + 1) >> 1, then min(mag, 2^MAG_W - 1). The kernel's two saturation
// tests need no code: either means Q >= 4^NB, so root >= 2^NB (sqrt is
// monotonic and exact at powers of four) and mag >= 2^MAG_W. root < 2^27
// (Q < 2^53): it fits an int32.
inline int32_t mag_fast(double re, double im, double scale, int32_t mag_max) {
  const double q = std::floor((re * re + im * im) * scale);
  const int32_t mag = (int32_t(std::sqrt(q)) + 1) >> 1;
  return mag < mag_max ? mag : mag_max;
}

// Magnitudes of the current sums into out[0..k). KP: the padded carrier
// count when known at compile time (0: a.kp).
template <int KP>
inline void mags_now(const Arrays& a, const MagCtx& m, int32_t* __restrict tmp, uint16_t* out) {
  const int kp = KP > 0 ? KP : a.kp, k = a.k;
  const int32_t* __restrict re = a.re;
  const int32_t* __restrict im = a.im;
  if (!m.fast) {
    for (int i = 0; i < k; ++i) out[i] = uint16_t(magnitude_exact(re[i], im[i], m.mw));
    return;
  }
  const double scale = m.scale;
  const int32_t mag_max = m.mag_max;
  for (int i = 0; i < kp; ++i) tmp[i] = mag_fast(re[i], im[i], scale, mag_max);
  for (int i = 0; i < k; ++i) out[i] = uint16_t(tmp[i]);
}

// What a frame writes: its K sums (re then im) or, fused into the sample
// loop (the sums are hot in registers), its K magnitudes.
struct FrameOut {
  int32_t* sums = nullptr;   // 2K per frame, when mags is null
  uint16_t* mags = nullptr;  // K per frame
  MagCtx m;
  int32_t* tmp = nullptr;    // kp lanes of scratch
};

// Samples x[0..n) through every carrier; at frame samples the K sums go to
// sums (re[0..K) then im[0..K), then the next frame).
// PACKED: C and -S in one int32 (CW <= 16); P: the product type (int32 when
// XW + CW <= 32, else int64); KP: the padded carrier count if fixed (8, 16:
// straight-line vector code, no loop overhead per sample), else 0.
// until: samples before the next frame sample (a frame after this sample
// when 0; step 0: never). Returns the frames written.
template <bool PACKED, class P, int KP, bool MAGS>
__attribute__((target_clones("avx512f", "avx2", "default")))
size_t run_block(const Arrays& a, const int32_t* x, size_t n, size_t& slot, uint64_t& until,
                 int step, const FrameOut& fo) {
  const P half = P(1) << (a.sh - 1);
  // Locals: with struct members the compiler must assume the stores alias
  // the loop bound and the pointers, and will not vectorise.
  const int kp = KP > 0 ? KP : a.kp, sh = a.sh, idx_shift = a.idx_shift, xs = a.xs;
  const uint32_t idx_mask = a.idx_mask;
  const uint32_t* __restrict inc = a.inc;
  uint32_t* __restrict phase = a.phase;
  int32_t* __restrict re = a.re;
  int32_t* __restrict im = a.im;
  const int32_t* __restrict packed = a.packed;
  const int32_t* __restrict cos_t = a.cos_t;
  const int32_t* __restrict nsin_t = a.nsin_t;
  size_t sets = 0;
  for (size_t i = 0; i < n; ++i) {
    const int32_t xi = int32_t(uint32_t(x[i]) << xs) >> xs;  // low XW bits, signed
    int32_t* __restrict rr = a.ring_re + slot * size_t(kp);
    int32_t* __restrict ri = a.ring_im + slot * size_t(kp);
    // Lanes are independent carriers: no dependence between iterations.
#pragma GCC ivdep
    for (int k = 0; k < kp; ++k) {
      const uint32_t th = phase[k];
      const uint32_t idx = (((th >> idx_shift) + 1u) >> 1) & idx_mask;
      P c, s;
      if constexpr (PACKED) {
        const int32_t v = packed[idx];
        c = P(v >> 16);
        s = P(int32_t(uint32_t(v) << 16) >> 16);
      } else {
        c = P(cos_t[idx]);
        s = P(nsin_t[idx]);
      }
      const int32_t tr = int32_t((P(xi) * c + half) >> sh);
      const int32_t ti = int32_t((P(xi) * s + half) >> sh);
      // Wrapping 32-bit sums: the exact window sum fits, so they equal it.
      re[k] = int32_t(uint32_t(re[k]) + uint32_t(tr) - uint32_t(rr[k]));
      im[k] = int32_t(uint32_t(im[k]) + uint32_t(ti) - uint32_t(ri[k]));
      rr[k] = tr;
      ri[k] = ti;
      phase[k] = th + inc[k];
    }
    slot = slot + 1 == a.n ? 0 : slot + 1;
    if (step <= 0) continue;
    if (until == 0) {
      if constexpr (MAGS) {
        mags_now<KP>(a, fo.m, fo.tmp, fo.mags + sets * size_t(a.k));
      } else {
        int32_t* out = fo.sums + sets * 2 * size_t(a.k);
        for (int k = 0; k < a.k; ++k) out[k] = re[k], out[a.k + k] = im[k];
      }
      ++sets;
      until = uint64_t(step);
    }
    --until;
  }
  return sets;
}

// carrier_magnitude's own digit-by-digit root (hls/carrier_magnitude.h),
// one instance per MAG_W = 1..16 (it depends on MAG_W only).
template <int... W>
constexpr std::array<uint32_t (*)(uint64_t), sizeof...(W) + 1> isqrt_table(
    std::integer_sequence<int, W...>) {
  return {nullptr, &hls::CarrierMagnitude<32, W + 1, 0>::isqrt_steps...};
}
constexpr auto kIsqrt = isqrt_table(std::make_integer_sequence<int, 16>{});

}  // namespace

void check_widths(const SdftWidthsRt& w, const MagnitudeWidths& mw) {
  if (w.n < 2 || w.n > 65536) throw std::invalid_argument(field("n", w.n, "2..65536"));
  if (w.xw < 2 || w.xw > 24) throw std::invalid_argument(field("xw", w.xw, "2..24"));
  if (w.cw < 3 || w.cw > 24) throw std::invalid_argument(field("cw", w.cw, "3..24"));
  if (w.tw < 3 || w.tw > 14) throw std::invalid_argument(field("tw", w.tw, "3..14"));
  if (w.fb < 0 || w.fb > w.cw - 2)
    throw std::invalid_argument(field("fb", w.fb, "0..CW-2 = " + std::to_string(w.cw - 2)));
  const int need = hls::sdft_min_acc_width(w.n, w.xw, w.fb);
  if (w.acc_w < need || w.acc_w > 32)
    throw std::invalid_argument(field("acc_w", w.acc_w,
                                      std::to_string(need) + "..32 (XW + 1 + FB + ceil(log2 N))"));
  if (!hls::sdft_widths_ok(w.n, w.xw, w.cw, w.tw, w.acc_w, w.fb))
    throw std::invalid_argument("sdft: widths rejected by hls::sdft_widths_ok");
  if (mw.acc_w != w.acc_w)
    throw std::invalid_argument(field("magnitude.acc_w", mw.acc_w, "the bank's ACC_W"));
  if (mw.mag_w < 1 || mw.mag_w > 16)
    throw std::invalid_argument(field("magnitude.mag_w", mw.mag_w, "1..16 (u16 packets)"));
  if (mw.shift < 0 || mw.shift > mw.acc_w)
    throw std::invalid_argument(field("magnitude.shift", mw.shift, "0..ACC_W"));
}

ExactSdft::ExactSdft(const SdftWidthsRt& w, std::vector<uint32_t> inc) : w_(w) {
  check_widths(w, MagnitudeWidths{w.acc_w, 16, 0});
  if (inc.empty() || inc.size() > 65536)
    throw std::invalid_argument("sdft.carriers: expected 1..65536 carriers, got " +
                                std::to_string(inc.size()));
  k_ = int(inc.size());
  kp_ = (k_ + kLanes - 1) / kLanes * kLanes;
  inc_ = std::move(inc);
  inc_.resize(size_t(kp_), 0u);  // padding lanes: phase 0, sample terms only
  // Full-circle tables from the kernel's quarter-wave rule (hls/sdft_bank.h
  // sine(): mirrored odd quadrants, negated upper half).
  const int q = 1 << (w.tw - 2), size = 1 << w.tw;
  const int32_t a = (int32_t(1) << (w.cw - 1)) - 1;
  std::vector<int32_t> quarter(size_t(q) + 1);
  for (int i = 0; i < q; ++i) quarter[size_t(i)] = hls::sdft_quarter_sine(i, q, w.cw);
  quarter[size_t(q)] = a;
  const auto sine = [&](uint32_t idx) {
    const uint32_t quad = (idx >> (w.tw - 2)) & 3u, o = idx & uint32_t(q - 1);
    const int32_t v = (quad & 1u) ? quarter[size_t(q) - o] : quarter[o];
    return (quad & 2u) ? -v : v;
  };
  cos_.resize(size_t(size));
  nsin_.resize(size_t(size));
  packed_.resize(size_t(size));
  for (uint32_t i = 0; i < uint32_t(size); ++i) {
    cos_[i] = sine(i + uint32_t(q));
    nsin_[i] = -sine(i);
    packed_[i] = int32_t((uint32_t(cos_[i]) << 16) | (uint32_t(nsin_[i]) & 0xffffu));
  }
  start_at(0);
}

void ExactSdft::start_at(uint64_t s) {
  phase_.assign(size_t(kp_), 0u);
  for (int k = 0; k < k_; ++k) phase_[size_t(k)] = uint32_t(s * uint64_t(inc_[size_t(k)]));
  re_.assign(size_t(kp_), 0);
  im_.assign(size_t(kp_), 0);
  ring_re_.assign(size_t(w_.n) * size_t(kp_), 0);
  ring_im_.assign(size_t(w_.n) * size_t(kp_), 0);
  slot_ = 0;
  next_ = s;
}

size_t ExactSdft::push_block(const int32_t* x, size_t n, const FrameClock& fc, int32_t* sums) {
  FrameOut fo;
  fo.sums = sums;
  return push(x, n, fc, fo);
}

size_t ExactSdft::push_block(const int32_t* x, size_t n, const FrameClock& fc,
                             const MagnitudeWidths& mw, uint16_t* mags) {
  tmp_.resize(size_t(kp_));
  FrameOut fo;
  fo.mags = mags;
  fo.m = make_mag_ctx(mw);
  fo.tmp = tmp_.data();
  return push(x, n, fc, fo);
}

template <class FO>
size_t ExactSdft::push(const int32_t* x, size_t n, const FrameClock& fc, const FO& fo) {
  const Arrays a{kp_, k_, inc_.data(), phase_.data(), re_.data(), im_.data(), ring_re_.data(),
                 ring_im_.data(), packed_.data(), cos_.data(), nsin_.data(), 31 - w_.tw,
                 w_.cw - 1 - w_.fb, 32 - w_.xw, (uint32_t(1) << w_.tw) - 1u, size_t(w_.n)};
  uint64_t until = 0;  // samples until the next frame sample
  if (fc.step > 0) {
    if (next_ < fc.first) {
      until = fc.first - next_;
    } else {
      const uint64_t r = (next_ - fc.first) % uint64_t(fc.step);
      until = r == 0 ? 0 : uint64_t(fc.step) - r;
    }
  }
  const bool packed = w_.cw <= 16, narrow = w_.xw + w_.cw <= 32;
  const auto run = [&](auto tag) {
    constexpr bool kMags = decltype(tag)::value;
    if (packed && narrow && kp_ == 8)
      return run_block<true, int32_t, 8, kMags>(a, x, n, slot_, until, fc.step, fo);
    if (packed && narrow && kp_ == 16)
      return run_block<true, int32_t, 16, kMags>(a, x, n, slot_, until, fc.step, fo);
    if (packed && narrow) return run_block<true, int32_t, 0, kMags>(a, x, n, slot_, until, fc.step, fo);
    if (narrow) return run_block<false, int32_t, 0, kMags>(a, x, n, slot_, until, fc.step, fo);
    return run_block<false, int64_t, 0, kMags>(a, x, n, slot_, until, fc.step, fo);
  };
  const size_t sets = fo.mags ? run(std::true_type{}) : run(std::false_type{});
  next_ += n;
  return sets;
}

bool magnitude_fast_ok(const MagnitudeWidths& mw) {
  // re^2 + im^2 < 2^(2 ACC_W - 1) <= 2^51 and Q <= 4P < 2^53: every double
  // operation of mag_fast is exact. floor(sqrt(Q)) of an integer Q < 2^52
  // is the exact integer root (sqrt is correctly rounded, and the gap below
  // the next integer m + 1 <= 2^26, at least 1/(2(m+1)), exceeds half its
  // ulp); Q >= 2^52 >= 4^NB (MAG_W + 1 <= 26) saturates either way.
  return mw.acc_w <= 26 && mw.mag_w + 1 <= 26;
}

uint32_t magnitude_exact(int32_t re, int32_t im, const MagnitudeWidths& mw) {
  const int nb = mw.mag_w + 1;
  const uint64_t mag_max = (uint64_t(1) << mw.mag_w) - 1u;
  const uint64_t ar = re < 0 ? uint64_t(0) - uint64_t(int64_t(re)) : uint64_t(re);
  const uint64_t ai = im < 0 ? uint64_t(0) - uint64_t(int64_t(im)) : uint64_t(im);
  const uint64_t p = ar * ar + ai * ai;
  uint64_t q;
  if (mw.shift == 0) {
    if (p >= (uint64_t(1) << (2 * nb - 2))) return uint32_t(mag_max);
    q = p << 2;
  } else {
    q = p >> (2 * mw.shift - 2);
  }
  if (q >= (uint64_t(1) << (2 * nb))) return uint32_t(mag_max);
  const uint64_t mag = (uint64_t(kIsqrt[size_t(mw.mag_w)](q)) + 1u) >> 1;
  return uint32_t(mag > mag_max ? mag_max : mag);
}

void magnitudes(const int32_t* re, const int32_t* im, int k, const MagnitudeWidths& mw,
                uint16_t* out) {
  const MagCtx m = make_mag_ctx(mw);
  for (int i = 0; i < k; ++i)
    out[i] = m.fast ? uint16_t(mag_fast(re[i], im[i], m.scale, m.mag_max))
                    : uint16_t(magnitude_exact(re[i], im[i], mw));
}

}  // namespace eskin::engine
