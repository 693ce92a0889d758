// The exact sliding DFT of hls/sdft_bank.h with runtime sizes, made fast
// for the host: the same integers, bit for bit (tests/engine/exact_sdft_test.cpp
// compares it with the kernel), at any K, N and widths chosen at run time.
//
// Why it can be faster than the kernel and still exact: the kernel subtracts
// T(x[n-N], theta(n-N)) by recomputing it from the stored sample and the
// re-derived phase; that is bit for bit the term it added N samples before.
// Here each added term is kept in a ring of N terms per carrier and
// subtracted from there, so a sample costs one table read and two
// multiplies per carrier (one 16-bit multiply for both with the top's
// widths on AVX2). Carriers go in blocks of 8 lanes (one AVX2 vector of
// int32, GCC vector extensions; AVX-512, AVX2 and baseline clones chosen at
// run time by GCC's target_clones), each block's phases and sums held in
// registers across a run of samples; the table reads skip padding lanes.
// Window sums never wrap (ACC_W >= XW + 1 + FB + ceil(log2 N), checked), so
// 32-bit two's complement sums equal the kernel's ACC_W-bit ones.
//
// Frame work only on frames: a window sum is the plain sum of its N exact
// terms, so where frames are sparse (a frame every `step` samples, N not
// much more than step) the frame's sums are computed directly from its N
// samples (N terms per carrier, no ring) and the samples between windows
// cost nothing. push_block chooses the cheaper way per call (FrameMode
// Auto) from N and step; both give the same numbers.
//
// Starting anywhere: zero samples add zero terms (R(0 * c) = 0), so a bank
// started at sample s with phase s * inc and an empty window, fed samples
// s .. s + N - 1, holds exactly the kernel's sums from then on. That is the
// warm-up that lets a long recording be split across threads exactly.
//
// Magnitudes: carrier_magnitude's correctly rounded |re + j im| >> SHIFT,
// in one pass over a run of frames' sums (K lanes a frame, no padding): a
// single-precision root checked exactly in double where that is exact (see
// magnitude_fast_ok), the kernel's own digit loop otherwise.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace eskin::engine {

struct SdftWidthsRt {
  int n = 32, xw = 12, cw = 16, tw = 10, acc_w = 18, fb = 0;
};

// Frame samples: s >= first with (s - first) % step == 0 (step 0: none).
struct FrameClock {
  uint64_t first = 0;
  int step = 0;
};

struct MagnitudeWidths {
  int acc_w = 18, mag_w = 16, shift = 2;
};

// How push_block computes frame sums: Auto picks the cheaper of the two
// for the call's N and step; the others force one (tests, benchmarks).
enum class FrameMode { Auto, Sliding, Direct };

class ExactSdft {
 public:
  // Throws std::invalid_argument naming the field ("sdft.acc_w: ...") when a
  // width breaks hls/sdft_bank.h's rules or there are no carriers.
  // pair_kernels false: the portable kernels even where the AVX2 term-pair
  // ones apply (the tests run both).
  ExactSdft(const SdftWidthsRt& w, std::vector<uint32_t> inc, bool pair_kernels = true);

  // Empty window, sums zero, phases of sample s (theta = s * inc mod 2^32).
  void start_at(uint64_t s);
  // Samples x[0..n) (ADC code minus mid code; the low XW bits are used).
  // After each frame sample of fc, the K sums go to sums (re[0..K) then
  // im[0..K); sums advances by 2K). Returns the number of frames written.
  size_t push_block(const int32_t* x, size_t n, const FrameClock& fc, int32_t* sums);
  // The same with the K magnitudes of each frame instead of its sums
  // (carrier_magnitude of the sums for mw; K u16 per frame), computed in
  // one pass over each run of frames while their sums are in cache.
  size_t push_block(const int32_t* x, size_t n, const FrameClock& fc, const MagnitudeWidths& mw,
                    uint16_t* mags);
  // The same without frames (warm-up).
  void push_block(const int32_t* x, size_t n) { push_block(x, n, FrameClock{}, nullptr); }

  void set_frame_mode(FrameMode m) { mode_ = m; }
  // True when push_block in Auto mode computes frames `step` apart directly.
  bool direct_for_step(int step) const;

  int carriers() const { return k_; }
  // The current window sums (samples next_sample() - N .. next_sample() - 1).
  int32_t re(int k) const;
  int32_t im(int k) const;
  uint64_t next_sample() const { return next_; }
  const SdftWidthsRt& widths() const { return w_; }

 private:
  struct Out;
  size_t push(const int32_t* x, size_t n, const FrameClock& fc, const Out& out);
  void resync();  // the sliding state from the last N samples
  int32_t window_sum(int k, bool imag) const;

  SdftWidthsRt w_;
  int k_ = 0, kp_ = 0;  // carriers, padded to a multiple of 8 (blocks of 8 lanes)
  FrameMode mode_ = FrameMode::Auto;
  // The top's widths on AVX2: both terms in one 16-bit multiply, the ring
  // holding term pairs (exact_sdft.cpp, slide_pairs).
  bool pairs_ = false;
  std::vector<uint32_t> inc_;
  std::vector<int32_t> cos_, nsin_;  // full 2^TW tables: C(idx), -S(idx)
  std::vector<int32_t> packed_;      // CW <= 16: C << 16 | (-S & 0xffff)
  // Sliding state (stale after direct frames, rebuilt from hist_ when
  // needed): per carrier phase and sums; per block of 8 carriers a ring of
  // N slots, each 8 real then 8 imaginary terms.
  std::vector<uint32_t> phase_;
  std::vector<int32_t> re_, im_, ring_;
  size_t slot_ = 0;
  bool stale_ = false;
  std::vector<int32_t> hist_;  // the last N samples, oldest first from hpos_ (2N, doubled)
  size_t hpos_ = 0;
  // Scratch: a run of frames' sums (re, im), direct frames' windows.
  std::vector<int32_t> fre_, fim_, win_;
  std::vector<const int32_t*> wptr_;
  std::vector<uint64_t> wfirst_;
  uint64_t next_ = 0;
};

// carrier_magnitude's result, min(floor(|re + j im| / 2^shift + 1/2), 2^mag_w - 1).
uint32_t magnitude_exact(int32_t re, int32_t im, const MagnitudeWidths& mw);
// True when the double-precision path of magnitudes() is exact for mw.
bool magnitude_fast_ok(const MagnitudeWidths& mw);
// K magnitudes (the fast path where exact, else the digit loop).
void magnitudes(const int32_t* re, const int32_t* im, int k, const MagnitudeWidths& mw,
                uint16_t* out);

// Throws std::invalid_argument naming the field unless the widths are
// legal for hls/sdft_bank.h and hls/carrier_magnitude.h.
void check_widths(const SdftWidthsRt& w, const MagnitudeWidths& mw);

}  // namespace eskin::engine
