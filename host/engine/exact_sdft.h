// The exact sliding DFT of hls/sdft_bank.h with runtime sizes, made fast
// for the host: the same integers, bit for bit (tests/engine/exact_sdft_test.cpp
// compares it with the kernel), at any K, N and widths chosen at run time.
//
// Why it can be faster than the kernel and still exact: the kernel subtracts
// T(x[n-N], theta(n-N)) by recomputing it from the stored sample and the
// re-derived phase; that is bit for bit the term it added N samples before.
// Here each added term is kept in a ring of N x K terms and subtracted from
// there, so a sample costs one table read and two multiplies per carrier,
// and the carrier loop (structure of arrays, padded to 16 lanes) is
// vectorised (AVX2/AVX-512 clones, chosen at run time). Window sums never
// wrap (ACC_W >= XW + 1 + FB + ceil(log2 N), checked), so 32-bit two's
// complement sums equal the kernel's ACC_W-bit ones.
//
// Starting anywhere: zero samples add zero terms (R(0 * c) = 0), so a bank
// started at sample s with phase s * inc and an empty window, fed samples
// s .. s + N - 1, holds exactly the kernel's sums from then on. That is the
// warm-up that lets a long recording be split across threads exactly.
//
// Magnitudes: carrier_magnitude's correctly rounded |re + j im| >> SHIFT,
// computed in double where that is exact (every product and the root below
// 2^52; see magnitude_fast_ok) and by the kernel's own digit loop otherwise.
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

class ExactSdft {
 public:
  // Throws std::invalid_argument naming the field ("sdft.acc_w: ...") when a
  // width breaks hls/sdft_bank.h's rules or there are no carriers.
  ExactSdft(const SdftWidthsRt& w, std::vector<uint32_t> inc);

  // Empty window, sums zero, phases of sample s (theta = s * inc mod 2^32).
  void start_at(uint64_t s);
  // Samples x[0..n) (ADC code minus mid code; the low XW bits are used).
  // After each frame sample of fc, the K sums go to sums (re[0..K) then
  // im[0..K); sums advances by 2K). Returns the number of frames written.
  size_t push_block(const int32_t* x, size_t n, const FrameClock& fc, int32_t* sums);
  // The same with the K magnitudes of each frame instead of its sums
  // (carrier_magnitude of the sums for mw; K u16 per frame), computed in
  // the sample loop while the sums are hot.
  size_t push_block(const int32_t* x, size_t n, const FrameClock& fc, const MagnitudeWidths& mw,
                    uint16_t* mags);
  // The same without frames (warm-up).
  void push_block(const int32_t* x, size_t n) { push_block(x, n, FrameClock{}, nullptr); }

  int carriers() const { return k_; }
  int32_t re(int k) const { return re_[size_t(k)]; }
  int32_t im(int k) const { return im_[size_t(k)]; }
  uint64_t next_sample() const { return next_; }
  const SdftWidthsRt& widths() const { return w_; }

 private:
  template <class FO>
  size_t push(const int32_t* x, size_t n, const FrameClock& fc, const FO& fo);

  SdftWidthsRt w_;
  int k_ = 0, kp_ = 0;  // carriers, padded to a multiple of 16
  std::vector<uint32_t> inc_, phase_;
  std::vector<int32_t> re_, im_;
  std::vector<int32_t> cos_, nsin_;  // full 2^TW tables: C(idx), -S(idx)
  std::vector<int32_t> packed_;      // CW <= 16: C << 16 | (-S & 0xffff)
  std::vector<int32_t> ring_re_, ring_im_;  // N x kp_ terms
  std::vector<int32_t> tmp_;                // magnitude scratch, kp_ lanes
  size_t slot_ = 0;
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
