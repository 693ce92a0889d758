#include "host/engine/exact_sdft.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include <immintrin.h>

#include "hls/carrier_magnitude.h"
#include "hls/sdft_bank.h"

namespace eskin::engine {
namespace {

constexpr int kLanes = 8;  // a block of carriers: one AVX2 vector of int32

// Sums of up to this many lanes (re and im each) per run of frames: the
// run's sums stay in L1 until its magnitudes are taken.
constexpr size_t kRunLanes = 2048;

// Sliding costs per frame `step` samples of (term + ring update), direct N
// terms: direct when N * kDirectCost < step * kSlideCost. The table reads
// dominate a term; the ring update adds about an eighth (measured: 6 to 128
// carriers, N 32 to 512, step N/2 to 3N/2, on an AVX-512 machine).
constexpr int kSlideCost = 8, kDirectCost = 7;

// Eight lanes of int32 (GCC vector extensions: one ymm register in the
// AVX2 and AVX-512 clones, two xmm in the default one). Memory goes through
// memcpy (unaligned loads and stores, no aliasing questions); vectors pass
// by reference (no ABI change between clones).
typedef int32_t VI __attribute__((vector_size(32)));
typedef uint32_t VU __attribute__((vector_size(32)));
typedef int64_t VL __attribute__((vector_size(64)));

template <class V>
inline void load(V& v, const void* p) {
  std::memcpy(&v, p, sizeof v);
}
template <class V>
inline void store(void* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}

std::string field(const char* name, int v, const std::string& expected) {
  return std::string("sdft.") + name + ": expected " + expected + ", got " + std::to_string(v);
}

// The tables and widths every term needs.
struct Tab {
  const int32_t* packed;
  const int32_t* cos_t;
  const int32_t* nsin_t;
  int idx_shift, sh, xs;
  uint32_t idx_mask;
  // The kernel's index ((th >> idx_shift) + 1) >> 1 & idx_mask is
  // floor((th + 2^idx_shift) / 2^(32-TW)) mod 2^TW, and wrapping th +
  // 2^idx_shift mod 2^32 drops only the quotient's bit TW: so the vector
  // kernels keep phases offset by half_step and take idx = ph >> idx_top.
  int idx_top;
  uint32_t half_step;
};

Tab tab(const SdftWidthsRt& w, const std::vector<int32_t>& packed,
        const std::vector<int32_t>& cos_t, const std::vector<int32_t>& nsin_t) {
  return Tab{packed.data(), cos_t.data(), nsin_t.data(), 31 - w.tw, w.cw - 1 - w.fb, 32 - w.xw,
             (uint32_t(1) << w.tw) - 1u, 32 - w.tw, uint32_t(1) << (31 - w.tw)};
}

// The low XW bits of a sample, sign-extended (as the kernel's ap_int<XW>).
inline int32_t sample(int32_t x, int xs) { return int32_t(uint32_t(x) << xs) >> xs; }

// The kernel's terms T = R(x C(idx)), R(x -S(idx)) for eight carriers at
// phases ph (offset by half_step): idx the phase rounded to TW bits, R rounding half up after the
// >> SH. PACKED: C and -S in one int32 (CW <= 16); WIDE: 64-bit products
// (XW + CW > 32). Without WIDE |x c| < 2^30, so int32 is exact. LIVE: the
// lanes holding carriers (the others get C = S = 0): the table reads are
// element by element, the cost of a term, so a bank of fewer than 8
// carriers skips the padding's.
template <bool PACKED, bool WIDE, int LIVE>
__attribute__((always_inline)) inline void terms(const Tab& t, const VU& ph, int32_t x, VI& tr,
                                                 VI& ti) {
  const VU idx = ph >> t.idx_top;
  VI c = {}, s = {};
  if constexpr (PACKED) {
    VI v = {};
    for (int l = 0; l < LIVE; ++l) v[l] = t.packed[idx[l]];
    c = v >> 16;
    s = VI(VU(v) << 16) >> 16;
  } else {
    for (int l = 0; l < LIVE; ++l) c[l] = t.cos_t[idx[l]], s[l] = t.nsin_t[idx[l]];
  }
  if constexpr (WIDE) {
    const int64_t half = int64_t(1) << (t.sh - 1);
    tr = __builtin_convertvector((__builtin_convertvector(c, VL) * int64_t(x) + half) >> t.sh, VI);
    ti = __builtin_convertvector((__builtin_convertvector(s, VL) * int64_t(x) + half) >> t.sh, VI);
  } else {
    const int32_t half = int32_t(1) << (t.sh - 1);
    tr = (c * x + half) >> t.sh;
    ti = (s * x + half) >> t.sh;
  }
}

// One term, as terms() computes it (64-bit products are exact for every width).
int32_t term1(const Tab& t, int32_t x, uint32_t th, bool imag) {
  const uint32_t idx = (((th >> t.idx_shift) + 1u) >> 1) & t.idx_mask;
  const int64_t c = imag ? t.nsin_t[idx] : t.cos_t[idx];
  return int32_t((int64_t(sample(x, t.xs)) * c + (int64_t(1) << (t.sh - 1))) >> t.sh);
}

// After sample i of a slide: the block's sums to the next frame's place
// (fre/fim + j * stride) when the sample is a frame sample (until 0, then
// `step` samples to the next; step 0: no frames). EVERY: every sample is
// frame i, without the bookkeeping.
template <bool EVERY>
__attribute__((always_inline)) inline void frame_out(const VI& r, const VI& m, size_t i, size_t& j,
                                                     uint64_t& until, int step, int32_t* fre,
                                                     int32_t* fim, size_t stride) {
  if constexpr (EVERY) {
    store(fre + i * stride, r), store(fim + i * stride, m);
    return;
  }
  if (step <= 0) return;
  if (until == 0) {
    store(fre + j * stride, r), store(fim + j * stride, m);
    ++j;
    until = uint64_t(step);
  }
  --until;
}

// One block of 8 carriers slides over samples x[0..n): its phases and sums
// (in registers for the whole run) and its ring of `slots` slots (from
// `slot`). until: samples before the next frame sample (0: this one; step
// 0: no frames); after the j-th frame sample the sums go to fre/fim +
// j * stride. EVERY: every sample is a frame (step 1, until 0; the
// amplitude workload), without the frame bookkeeping.
template <bool PACKED, bool WIDE, int LIVE, bool EVERY>
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void slide_block(const Tab& tab, const int32_t* __restrict x, size_t n, uint32_t* phase,
                 const uint32_t* inc, int32_t* re, int32_t* im, int32_t* __restrict ring,
                 size_t slots, size_t slot, uint64_t until, int step, int32_t* __restrict fre,
                 int32_t* __restrict fim, size_t stride) {
  const Tab t = tab;  // a local copy: the stores below cannot change it
  VU ph, dph;
  VI r, m;
  load(ph, phase), load(dph, inc), load(r, re), load(m, im);
  ph += t.half_step;
  const int xs = t.xs;
  size_t j = 0;
  for (size_t i = 0; i < n; ++i) {
    VI tr, ti, old_r, old_i;
    terms<PACKED, WIDE, LIVE>(t, ph, sample(x[i], xs), tr, ti);
    int32_t* rs = ring + slot * 2 * kLanes;
    load(old_r, rs), load(old_i, rs + kLanes);
    // Wrapping 32-bit sums: the exact window sum fits, so they equal it.
    r = VI(VU(r) + VU(tr) - VU(old_r));
    m = VI(VU(m) + VU(ti) - VU(old_i));
    store(rs, tr), store(rs + kLanes, ti);
    ph += dph;
    slot = slot + 1 == slots ? 0 : slot + 1;
    frame_out<EVERY>(r, m, i, j, until, step, fre, fim, stride);
  }
  ph -= t.half_step;
  store(phase, ph), store(re, r), store(im, m);
}

// Frames computed directly: frame f's sums are the sums of the N terms of
// its window win[f][0..N), whose first sample is first[f] (phase first[f] *
// inc); every block of 8 carriers, into fre/fim + f * stride.
template <bool PACKED, bool WIDE, int LIVE>
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void direct_frames(const Tab& tab, const int32_t* const* win, const uint64_t* first, size_t frames,
                   size_t n, const uint32_t* inc, int blocks, int32_t* __restrict fre,
                   int32_t* __restrict fim, size_t stride) {
  const Tab t = tab;
  const int xs = t.xs;
  for (size_t f = 0; f < frames; ++f) {
    const int32_t* __restrict w = win[f];
    for (int b = 0; b < blocks; ++b) {
      VU dph;
      load(dph, inc + b * kLanes);
      VU ph = dph * uint32_t(first[f]) + t.half_step;
      VI r = {}, m = {};
      for (size_t j = 0; j < n; ++j) {
        VI tr, ti;
        terms<PACKED, WIDE, LIVE>(t, ph, sample(w[j], xs), tr, ti);
        r = VI(VU(r) + VU(tr)), m = VI(VU(m) + VU(ti));
        ph += dph;
      }
      store(fre + f * stride + size_t(b) * kLanes, r);
      store(fim + f * stride + size_t(b) * kLanes, m);
    }
  }
}

// The top's widths (CW 16, FB 0: SH 15; XW <= 14) on AVX2: both terms of a
// carrier in one 16-bit multiply. The packed entry is C : -S as two int16
// lanes, and vpmulhrsw computes (a b + 2^14) >> 15 per lane: R(x C) and
// R(x -S) at once, the terms T_re : T_im as int16 lanes (|T| <= 2^13). The
// ring keeps those pairs (8 lanes a slot); a new minus an old term is exact
// in int16 (|difference| <= 2^14), then widened into the sums. The same
// numbers as terms(), fewer instructions (the unpacking and the 32-bit
// multiplies go). Chosen at run time (ExactSdft::pairs_).
template <int LIVE, bool EVERY>
__attribute__((target("arch=x86-64-v3")))
void slide_pairs(const Tab& tab, const int32_t* __restrict x, size_t n, uint32_t* phase,
                 const uint32_t* inc, int32_t* re, int32_t* im, int32_t* __restrict ring,
                 size_t slots, size_t slot, uint64_t until, int step, int32_t* __restrict fre,
                 int32_t* __restrict fim, size_t stride) {
  const Tab t = tab;
  VU ph, dph;
  VI r, m;
  load(ph, phase), load(dph, inc), load(r, re), load(m, im);
  ph += t.half_step;
  const int xs = t.xs;
  size_t j = 0;
  for (size_t i = 0; i < n; ++i) {
    const VU idx = ph >> t.idx_top;
    VI v = {};
    for (int l = 0; l < LIVE; ++l) v[l] = t.packed[idx[l]];
    const __m256i tp =
        _mm256_mulhrs_epi16(__m256i(v), _mm256_set1_epi16(int16_t(sample(x[i], xs))));
    int32_t* rs = ring + slot * kLanes;
    __m256i old;
    load(old, rs);
    store(rs, tp);
    const VI d = VI(_mm256_sub_epi16(tp, old));
    r = VI(VU(r) + VU(d >> 16));
    m = VI(VU(m) + VU(VI(VU(d) << 16) >> 16));
    ph += dph;
    slot = slot + 1 == slots ? 0 : slot + 1;
    frame_out<EVERY>(r, m, i, j, until, step, fre, fim, stride);
  }
  ph -= t.half_step;
  store(phase, ph), store(re, r), store(im, m);
}

template <int LIVE>
__attribute__((target("arch=x86-64-v3")))
void direct_pairs(const Tab& tab, const int32_t* const* win, const uint64_t* first, size_t frames,
                  size_t n, const uint32_t* inc, int blocks, int32_t* __restrict fre,
                  int32_t* __restrict fim, size_t stride) {
  const Tab t = tab;
  const int xs = t.xs;
  for (size_t f = 0; f < frames; ++f) {
    const int32_t* __restrict w = win[f];
    for (int b = 0; b < blocks; ++b) {
      VU dph;
      load(dph, inc + b * kLanes);
      VU ph = dph * uint32_t(first[f]) + t.half_step;
      VI r = {}, m = {};
      for (size_t j = 0; j < n; ++j) {
        const VU idx = ph >> t.idx_top;
        VI v = {};
        for (int l = 0; l < LIVE; ++l) v[l] = t.packed[idx[l]];
        const VI tp = VI(
            _mm256_mulhrs_epi16(__m256i(v), _mm256_set1_epi16(int16_t(sample(w[j], xs)))));
        r = VI(VU(r) + VU(tp >> 16)), m = VI(VU(m) + VU(VI(VU(tp) << 16) >> 16));
        ph += dph;
      }
      store(fre + f * stride + size_t(b) * kLanes, r);
      store(fim + f * stride + size_t(b) * kLanes, m);
    }
  }
}

// The kernels for 16-bit tables by live lanes (2, 4, 6 or 8).
using SlideFn = decltype(&slide_block<true, false, kLanes, false>);
using DirectFn = decltype(&direct_frames<true, false, kLanes>);
template <bool EVERY>
SlideFn packed_slide(int live) {
  return live == 2   ? &slide_block<true, false, 2, EVERY>
         : live == 4 ? &slide_block<true, false, 4, EVERY>
         : live == 6 ? &slide_block<true, false, 6, EVERY>
                     : &slide_block<true, false, kLanes, EVERY>;
}
DirectFn packed_direct(int live) {
  return live == 2   ? &direct_frames<true, false, 2>
         : live == 4 ? &direct_frames<true, false, 4>
         : live == 6 ? &direct_frames<true, false, 6>
                     : &direct_frames<true, false, kLanes>;
}
template <bool EVERY>
SlideFn pairs_slide(int live) {
  return live == 2   ? &slide_pairs<2, EVERY>
         : live == 4 ? &slide_pairs<4, EVERY>
         : live == 6 ? &slide_pairs<6, EVERY>
                     : &slide_pairs<kLanes, EVERY>;
}
DirectFn pairs_direct(int live) {
  return live == 2   ? &direct_pairs<2>
         : live == 4 ? &direct_pairs<4>
         : live == 6 ? &direct_pairs<6>
                     : &direct_pairs<kLanes>;
}

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

// carrier_magnitude's min(((floor(sqrt(Q)) + 1) >> 1), 2^MAG_W - 1), Q =
// floor(P / 4^(SHIFT-1)) (4P for SHIFT 0), P = re^2 + im^2, for n lanes,
// exact when magnitude_fast_ok; vectorised in chunks of 64. A root in
// double precision would cost most of a frame's work, so a chunk first
// runs in single precision: z = P / 4^(SHIFT-1) (4P) in float (relative
// error <= 2^-23 when re and im convert exactly, ACC_W <= 25, else 2^-22;
// in double z is exact), clamped to 4^NB (NB = MAG_W + 1), t =
// floor(sqrtf(z)) (the truncating conversion of a non-negative number is
// its floor). Unless it saturates, sqrt(z) <= 2^17, so
// |sqrtf(z) - sqrt(z)| < 2^-5; and sqrt(z) < sqrt(Q) + 1/2 for Q =
// floor(z) >= 1, z < 1 for Q = 0: t is the root r = floor(sqrt(Q)) give or
// take 1. With b = t | 1 (odd),
// mag = (r + 1) >> 1 = (b >> 1) + [Q >= b^2] for each of t = r - 1, r,
// r + 1 (the parities work out), and Q >= b^2 iff z >= b^2 (b^2 is an
// integer). That test is decided in float where |z - b^2| exceeds both
// roundings (bounded by (z + b^2) tol, tol twice the relative error; a
// rounded difference keeps its sign); a chunk with any lane too close is
// redone exactly in double (z and b^2 < 2^53). The kernel's two saturation
// tests both mean Q >= 4^NB: then t >= 2^NB - 1 (sqrt is monotonic and
// exact at powers of four) and the rule gives mag >= 2^MAG_W, as does a
// clamped t = 2^NB (b >> 1 = 2^MAG_W); min() saturates either. Magnitudes
// of a few thousand need the exact pass in a few percent of chunks;
// full-scale ones in most (then it costs about what a double root would).
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void mags_fast(const int32_t* __restrict re, const int32_t* __restrict im, size_t n, double scale,
               int32_t mag_max, int mag_w, float tol, uint16_t* __restrict out) {
  constexpr size_t kChunk = 64;
  const float scale_f = float(scale), z_max = std::ldexp(1.0f, 2 * (mag_w + 1));
  for (size_t a = 0; a < n; a += kChunk) {
    const size_t len = std::min(kChunk, n - a);
    const int32_t* __restrict cr = re + a;
    const int32_t* __restrict ci = im + a;
    uint16_t* __restrict co = out + a;
    int close = 0;
    for (size_t i = 0; i < len; ++i) {
      const float rf = float(cr[i]), mf = float(ci[i]);
      float z = (rf * rf + mf * mf) * scale_f;
      z = z < z_max ? z : z_max;
      const int32_t b = int32_t(std::sqrt(z)) | 1;
      const float bf = float(b), b2 = bf * bf, d = z - b2;
      close |= std::fabs(d) <= (z + b2) * tol;
      const int32_t mag = (b >> 1) + (d > 0.0f ? 1 : 0);
      co[i] = uint16_t(mag < mag_max ? mag : mag_max);
    }
    if (!close) continue;
    // t again (it may round differently here: any t within 1 of r will do).
    for (size_t i = 0; i < len; ++i) {
      const float rf = float(cr[i]), mf = float(ci[i]);
      float z = (rf * rf + mf * mf) * scale_f;
      z = z < z_max ? z : z_max;
      const int32_t b = int32_t(std::sqrt(z)) | 1;
      const double rd = cr[i], md = ci[i], bd = b;
      const int32_t mag = (b >> 1) + ((rd * rd + md * md) * scale >= bd * bd ? 1 : 0);
      co[i] = uint16_t(mag < mag_max ? mag : mag_max);
    }
  }
}

void mags_any(const int32_t* re, const int32_t* im, size_t n, const MagCtx& m, uint16_t* out) {
  if (m.fast)
    return mags_fast(re, im, n, m.scale, m.mag_max, m.mw.mag_w,
                     m.mw.acc_w <= 25 ? 0x1p-22f : 0x1p-21f, out);
  for (size_t i = 0; i < n; ++i) out[i] = uint16_t(magnitude_exact(re[i], im[i], m.mw));
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

ExactSdft::ExactSdft(const SdftWidthsRt& w, std::vector<uint32_t> inc, bool pair_kernels)
    : w_(w) {
  check_widths(w, MagnitudeWidths{w.acc_w, 16, 0});
  if (inc.empty() || inc.size() > 65536)
    throw std::invalid_argument("sdft.carriers: expected 1..65536 carriers, got " +
                                std::to_string(inc.size()));
  k_ = int(inc.size());
  kp_ = (k_ + kLanes - 1) / kLanes * kLanes;
  pairs_ = pair_kernels && w.cw == 16 && w.fb == 0 && w.xw <= 14 &&
           __builtin_cpu_supports("avx2");
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
  ring_.assign(size_t(w_.n) * (pairs_ ? 1 : 2) * size_t(kp_), 0);
  hist_.assign(2 * size_t(w_.n), 0);
  hpos_ = 0;
  slot_ = 0;
  stale_ = false;
  next_ = s;
}

bool ExactSdft::direct_for_step(int step) const {
  return step > 0 && int64_t(w_.n) * kDirectCost < int64_t(step) * kSlideCost;
}

int32_t ExactSdft::window_sum(int k, bool imag) const {
  const Tab t = tab(w_, packed_, cos_, nsin_);
  uint32_t sum = 0;
  const uint64_t s0 = next_ - uint64_t(w_.n);  // wraps before sample N: zero samples there
  const int32_t* h = hist_.data() + hpos_;
  for (int j = 0; j < w_.n; ++j)
    sum += uint32_t(term1(t, h[j], uint32_t(s0 + uint64_t(j)) * inc_[size_t(k)], imag));
  return int32_t(sum);
}

int32_t ExactSdft::re(int k) const { return stale_ ? window_sum(k, false) : re_[size_t(k)]; }
int32_t ExactSdft::im(int k) const { return stale_ ? window_sum(k, true) : im_[size_t(k)]; }

// The ring holds the terms of the last N samples; rebuilt in sample order
// (slot 0: the oldest, the next one to leave), the sums are their sums.
void ExactSdft::resync() {
  const Tab t = tab(w_, packed_, cos_, nsin_);
  const size_t n = size_t(w_.n);
  const uint64_t s0 = next_ - n;
  const int32_t* h = hist_.data() + hpos_;
  for (int k = 0; k < kp_; ++k) {
    const size_t b = size_t(k / kLanes), l = size_t(k % kLanes);
    uint32_t sr = 0, si = 0;
    for (size_t j = 0; j < n; ++j) {
      const uint32_t th = uint32_t(s0 + j) * inc_[size_t(k)];
      const int32_t tr = term1(t, h[j], th, false), ti = term1(t, h[j], th, true);
      if (pairs_) {
        ring_[(b * n + j) * kLanes + l] = int32_t((uint32_t(tr) << 16) | (uint32_t(ti) & 0xffffu));
      } else {
        int32_t* slot = ring_.data() + (b * n + j) * 2 * kLanes;
        slot[l] = tr, slot[kLanes + l] = ti;
      }
      sr += uint32_t(tr), si += uint32_t(ti);
    }
    re_[size_t(k)] = int32_t(sr), im_[size_t(k)] = int32_t(si);
    phase_[size_t(k)] = uint32_t(next_) * inc_[size_t(k)];
  }
  slot_ = 0;
  stale_ = false;
}

struct ExactSdft::Out {
  int32_t* sums = nullptr;   // 2K per frame, when mags is null
  uint16_t* mags = nullptr;  // K per frame
  MagnitudeWidths mw;
};

size_t ExactSdft::push_block(const int32_t* x, size_t n, const FrameClock& fc, int32_t* sums) {
  Out o;
  o.sums = sums;
  return push(x, n, fc, o);
}

size_t ExactSdft::push_block(const int32_t* x, size_t n, const FrameClock& fc,
                             const MagnitudeWidths& mw, uint16_t* mags) {
  Out o;
  o.mags = mags;
  o.mw = mw;
  return push(x, n, fc, o);
}

size_t ExactSdft::push(const int32_t* x, size_t n, const FrameClock& fc, const Out& out) {
  const int step = fc.step;
  uint64_t until = 0;  // samples until the next frame sample
  if (step > 0) {
    if (next_ < fc.first) {
      until = fc.first - next_;
    } else {
      const uint64_t r = (next_ - fc.first) % uint64_t(step);
      until = r == 0 ? 0 : uint64_t(step) - r;
    }
  }
  // Direct frames when asked or cheaper; without frames a forced Direct
  // only keeps the history (the sums are rebuilt if read).
  const bool direct =
      mode_ == FrameMode::Direct || (mode_ == FrameMode::Auto && direct_for_step(step));
  if (!direct && stale_) resync();
  const Tab t = tab(w_, packed_, cos_, nsin_);
  // Kernels: 16-bit tables (the top's) by live lanes (K rounded up to even,
  // one block), others with all 8.
  const bool packed = w_.cw <= 16, narrow = w_.xw + w_.cw <= 32;
  const int blocks = kp_ / kLanes, live = blocks > 1 ? kLanes : (k_ + 1) / 2 * 2;
  auto slide = &slide_block<false, true, kLanes, false>;
  auto direct_fn = &direct_frames<false, true, kLanes>;
  if (packed && narrow) {
    // A frame every sample (step 1): the kernel without the frame clock.
    const bool every = step == 1 && until == 0;
    slide = every ? packed_slide<true>(live) : packed_slide<false>(live);
    direct_fn = packed_direct(live);
    if (pairs_) {
      slide = every ? pairs_slide<true>(live) : pairs_slide<false>(live);
      direct_fn = pairs_direct(live);
    }
  } else if (narrow) {
    slide = &slide_block<false, false, kLanes, false>;
    direct_fn = &direct_frames<false, false, kLanes>;
  }
  const size_t win = size_t(w_.n);
  // One block: frames K apart in the scratch (a vector store spills into
  // the next frame's lanes, rewritten after); more: kp_ apart.
  const size_t stride = blocks == 1 ? size_t(k_) : size_t(kp_);
  const size_t run_frames = std::max<size_t>(1, kRunLanes / stride);
  if (step > 0) {
    fre_.resize(run_frames * stride + kLanes);
    fim_.resize(run_frames * stride + kLanes);
  }
  const MagCtx mc = make_mag_ctx(out.mw);
  size_t total = 0;
  for (size_t a = 0; a < n;) {
    // A run: samples [a, a + len) holding at most run_frames frame samples.
    size_t len = n - a;
    if (step > 0)
      len = size_t(std::min<uint64_t>(len, until + uint64_t(run_frames - 1) * uint64_t(step) + 1));
    const size_t got = step > 0 && until < len ? size_t((len - 1 - until) / uint64_t(step)) + 1 : 0;
    if (direct) {
      // Frame j's newest sample is a + until + j step; a window starting
      // before x[0] is assembled from the history (one window at a time).
      wptr_.clear(), wfirst_.clear();
      size_t done = 0;
      for (size_t j = 0; j < got; ++j) {
        const size_t q = a + size_t(until) + j * size_t(step);  // in x
        const uint64_t first = next_ + q + 1 - win;
        if (q + 1 >= win) {
          wptr_.push_back(x + (q + 1 - win)), wfirst_.push_back(first);
          continue;
        }
        win_.resize(win);
        const int32_t* h = hist_.data() + hpos_;
        std::copy(h + q + 1, h + win, win_.begin());
        std::copy(x, x + q + 1, win_.begin() + ptrdiff_t(win - q - 1));
        const int32_t* w = win_.data();
        direct_fn(t, &w, &first, 1, win, inc_.data(), blocks, fre_.data() + j * stride,
                  fim_.data() + j * stride, stride);
        done = j + 1;
      }
      direct_fn(t, wptr_.data(), wfirst_.data(), wptr_.size(), win, inc_.data(), blocks,
                fre_.data() + done * stride, fim_.data() + done * stride, stride);
    } else {
      for (int b = 0; b < blocks; ++b) {
        const size_t o = size_t(b) * kLanes;
        slide(t, x + a, len, phase_.data() + o, inc_.data() + o, re_.data() + o, im_.data() + o,
              ring_.data() + size_t(b) * win * (pairs_ ? 1 : 2) * kLanes, win, slot_, until, step,
              fre_.data() + o, fim_.data() + o, stride);
      }
      slot_ = (slot_ + len) % win;
    }
    if (got > 0) {
      const size_t k = size_t(k_);
      if (out.mags && stride == k) {
        mags_any(fre_.data(), fim_.data(), got * k, mc, out.mags + total * k);
      } else {
        for (size_t j = 0; j < got; ++j) {
          const int32_t* fr = fre_.data() + j * stride;
          const int32_t* fi = fim_.data() + j * stride;
          if (out.mags) {
            mags_any(fr, fi, k, mc, out.mags + (total + j) * k);
          } else {
            int32_t* o = out.sums + (total + j) * 2 * k;
            std::copy(fr, fr + k, o), std::copy(fi, fi + k, o + k);
          }
        }
      }
      until = uint64_t(step) - 1 - (len - 1 - until) % uint64_t(step);
    } else if (step > 0) {
      until -= len;
    }
    total += got;
    a += len;
  }
  // The history: the last N samples, each written twice (a ring of N read
  // as one contiguous window from hpos_).
  for (size_t i = n > win ? n - win : 0; i < n; ++i) {
    hist_[hpos_] = hist_[hpos_ + win] = x[i];
    hpos_ = hpos_ + 1 == win ? 0 : hpos_ + 1;
  }
  next_ += n;
  if (direct) stale_ = true;
  return total;
}

bool magnitude_fast_ok(const MagnitudeWidths& mw) {
  // re^2 + im^2 < 2^(2 ACC_W - 1) <= 2^51 and z <= 4P < 2^53: mags_fast's
  // double-precision test is exact; MAG_W <= 16 keeps an unsaturated root
  // at most 2^17, where its single-precision estimate is within 1.
  return mw.acc_w <= 26 && mw.mag_w >= 1 && mw.mag_w <= 16;
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
  mags_any(re, im, size_t(k), make_mag_ctx(mw), out);
}

}  // namespace eskin::engine
