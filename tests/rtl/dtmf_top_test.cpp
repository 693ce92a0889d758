// System test of the DTMF FPGA path: scene -> world model -> AD7476A pin
// model -> Verilated rtl/dtmf_top.v -> UART line sampled bit by bit ->
// host/link LinkDecoder -> packets, compared with hls/dtmf_chain.h run on
// the same samples.
//
// Samples: the world model's 10-bit codes c10 are served as 12-bit codes
// c10 << 2 (the AD7476A's width, left aligned); the chain subtracts 2048 and
// its magnitude shift of 2 undoes the alignment (hls/dtmf_chain.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Vdtmf_top.h"
#include "Vdtmf_top___024root.h"
#include "Vdtmf_top_cc.h"
#include "Vdtmf_top_cc___024root.h"
#include "Vdtmf_top_s16.h"
#include "Vdtmf_top_s16___024root.h"
#include "eskin/skin_config.h"
#include "hls/dtmf_chain.h"
#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank_config.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "sim/ad7476_model.h"
#include "sim/scene.h"
#include "sim/world_model.h"

#include "dtmf_top_board.h"

namespace {

using namespace dtmf_bench;
using eskin::link::Packet;

// The default scene's chain (3x3, N = 32: the top's default parameters)
// and the 16x16 build (tests/rtl/dtmf_top_test.cmake).
// Widths: XW = 12 (code - 2048), ACC_W = XW + 1 + log2 N, CW 16, TW 10.
using Chain3 = eskin::hls::DtmfChain<3, 3, 32, 12, 16, 10, 18>;
using Chain16 = eskin::hls::DtmfChain<16, 16, 128, 12, 16, 10, 20>;

// Host-side chain configuration from a scene: carriers as phase increments,
// conductance taxels (recip from the full-carrier window magnitude in 10-bit
// code units: N/2 * full_carrier_lsb), the scene's neuron at dt = step / fs.
template <class Chain>
typename Chain::Config chain_config(const eskin::sim::Scene& sc, int step, uint16_t decim,
                                    uint8_t mask) {
  typename Chain::Config c;
  const auto f = sc.skin.carrier_freqs_hz();
  const double fs = sc.skin.adc.rate_hz;
  c.sdft.carriers = int(f.size());
  for (size_t k = 0; k < f.size(); ++k) c.sdft.inc[k] = eskin::hls::sdft_phase_increment(f[k], fs);
  c.taxel.rows = uint8_t(sc.skin.rows);
  c.taxel.cols = uint8_t(sc.skin.cols);
  c.taxel.mode = eskin::hls::TaxelMode::Conductance;
  c.taxel.recip_shift = 12;
  const double full = sc.decoder.window / 2.0 * sc.skin.full_carrier_lsb();
  c.taxel.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + 12) / full));
  c.neuron = eskin::hls::make_izhikevich_config(
      eskin::hls::izhikevich_fixed_preset(sc.neuron.preset), step * 1000.0 / fs,
      sc.neuron.input_scale / 32768.0, 1);
  c.step = step;
  c.decim_amp = decim;
  c.decim_tax = decim;
  c.mask = mask;
  return c;
}

template <class Chain>
std::vector<Key> run_chain(Chain& chain, const std::vector<uint16_t>& codes12, size_t n) {
  std::vector<Key> out;
  auto pk = std::make_unique<typename Chain::Packet[]>(3);
  typename Chain::Packet(&p3)[3] = *reinterpret_cast<typename Chain::Packet(*)[3]>(pk.get());
  for (size_t i = 0; i < n; ++i) {
    const int np = chain.push(codes12[i], uint32_t(i), p3);
    for (int j = 0; j < np; ++j)
      out.push_back({p3[j].type, p3[j].t, {p3[j].payload, p3[j].payload + p3[j].len}});
  }
  return out;
}

std::vector<uint16_t> scene_codes12(const eskin::sim::Scene& sc) {
  eskin::sim::WorldModel world(sc);
  std::vector<uint16_t> c;
  for (int v : world.all_codes()) c.push_back(uint16_t(v << (12 - sc.skin.adc.bits)));
  return c;
}

// Packets of `type` whose data is complete before sample `limit`
// (amplitudes/taxels: t < limit; spikes: window end t + span <= limit).
std::vector<Key> of_type(const std::vector<Key>& all, uint8_t type, uint32_t limit,
                         uint32_t span) {
  std::vector<Key> r;
  for (const Key& k : all) {
    if (k.type != type) continue;
    if ((type == eskin::link::kSpikes ? k.t + span : k.t) >= limit) continue;
    r.push_back(k);
  }
  return r;
}

std::vector<Key> keys(const std::vector<Received>& rx) {
  std::vector<Key> got;
  for (const auto& r : rx) got.push_back({r.p.type, r.p.t, r.p.payload});
  return got;
}

// Per type, the RTL's packets equal the chain's, in order.
void expect_same_packets(const std::vector<Key>& want, const std::vector<Key>& got,
                         uint32_t limit, uint32_t span, std::vector<uint8_t> types,
                         size_t min_each) {
  for (uint8_t type : types) {
    const auto w = of_type(want, type, limit, span);
    const auto g = of_type(got, type, limit, span);
    EXPECT_GE(w.size(), min_each) << "type " << int(type) << ": too few packets to compare";
    ASSERT_EQ(g.size(), w.size()) << "type " << int(type);
    for (size_t i = 0; i < w.size(); ++i)
      ASSERT_EQ(g[i], w[i]) << "type " << int(type) << " packet " << i << "\n got  " << str(g[i])
                            << "\n want " << str(w[i]);
  }
}

// Link and pin-level health of a run.
template <class M>
void expect_clean_run(Board<M>& b) {
  EXPECT_EQ(b.link_stats().crc_errors + b.link_stats().framing_errors +
                b.link_stats().payload_errors, 0u);
  EXPECT_EQ(b.link_stats().lost_packets, 0u);
  EXPECT_EQ(b.uart_framing_errors(), 0);
  EXPECT_EQ(b.adc().violation_count(), 0u)
      << (b.adc().violations().empty() ? "" : b.adc().violations()[0]);
  EXPECT_FALSE(b.tag_error);
  // Throughput: no ADC sample lost, no packet dropped for a busy link.
  EXPECT_EQ(b.root().dtmf_top__DOT__p_overruns, 0);
  EXPECT_EQ(b.root().dtmf_top__DOT__p_dropped, 0);
}

const eskin::sim::Scene& default_scene() {
  static const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  return sc;
}
constexpr std::initializer_list<uint8_t> kDataTypes = {
    eskin::link::kAmplitudes, eskin::link::kTaxelsDense, eskin::link::kSpikes};

// Bound: exact equality. Every block of the path is the bit-exact RTL of its
// HLS kernel (their own tests), the glue (tag FIFOs, step gate, packetizer)
// only moves data, and the link is lossless (CRC checked by the decoder), so
// any difference in type, t or a payload byte is a bug. The whole 0.6 s
// scene (21000 samples, every press) is compared.
TEST(DtmfTop, DefaultSceneMatchesHlsChainPacketForPacket) {
  const auto& scene = default_scene();
  ASSERT_EQ(scene.skin.rows, 3);
  ASSERT_EQ(scene.skin.cols, 3);
  ASSERT_EQ(scene.decoder.window, 32);
  ASSERT_EQ(scene.skin.adc.bits, 10);
  auto codes = scene_codes12(scene);
  const size_t n = codes.size();
  const size_t pad = 64;  // extra conversions so the last frames get out
  codes.resize(n + pad, 2048);

  const uint16_t decim = 35;  // top defaults: 35 steps, mask 0xF
  auto chain = std::make_unique<Chain3>(chain_config<Chain3>(scene, 1, decim, 7));
  ASSERT_TRUE(chain->ok());
  const auto want = run_chain(*chain, codes, n);

  Board<Vdtmf_top> b(codes);
  b.run_until_sample(n + pad - 1);
  expect_clean_run(b);
  expect_same_packets(want, keys(b.received()), uint32_t(n) - decim, decim, kDataTypes, 10);

  // Periodic status (mask bit 3, every 1000 steps): counters all clean.
  int status = 0;
  for (const auto& r : b.received()) {
    if (r.p.type != eskin::link::kStatus) continue;
    ++status;
    EXPECT_EQ(r.p.status.output_mask, 0x0F);
    EXPECT_EQ(r.p.status.adc_overruns + r.p.status.dropped_frames + r.p.status.uart_rx_errors +
                  r.p.status.cmd_crc_errors + r.p.status.cmd_frame_errors, 0);
    EXPECT_LE(r.p.status.samples, n + pad);
  }
  EXPECT_EQ(status, int((n + pad - 1) / 1000) + 1);  // steps 0, 1000, ...
  std::printf("dtmf_top: %zu samples, %zu packets received, %llu cycles (%.1f per sample)\n", n,
              b.received().size(), (unsigned long long)b.cycle(), double(b.cycle()) / double(n + pad));
}

// "A scene that wants only spikes gets only spikes": SET_OUTPUT_MASK(0x04)
// through uart_rx; afterwards (once the packets already buffered or in
// flight are out: two frame periods) only spike packets and the requested
// status arrive. The spike stream itself is unchanged: equal to the chain's
// for the whole run. A command frame with one corrupted byte is dropped and
// counted (CRC or framing error), changes nothing, and the data path keeps
// running; REQUEST_STATUS then reports the counters.
TEST(DtmfTop, SpikesOnlyCommandAndCorruptedFrame) {
  const auto& scene = default_scene();
  auto codes = scene_codes12(scene);
  const size_t n = 9000;  // presses of taxels (0,0) .. (1,1): spikes from ~sample 400
  codes.resize(n + 64);
  const uint16_t decim = 35;
  auto chain = std::make_unique<Chain3>(chain_config<Chain3>(scene, 1, decim, 7));
  const auto want = run_chain(*chain, codes, n);

  Board<Vdtmf_top> b(codes);
  eskin::link::LinkEncoder enc;
  b.run_until_sample(2000);
  b.send(enc.set_output_mask(eskin::hls::kMaskSpikes));
  b.run_until_sample(3000);
  auto bad = enc.request_status();
  bad[bad.size() - 3] ^= (bad[bad.size() - 3] == 0x01) ? 0x02 : 0x01;  // stays non-zero
  b.send(bad);
  b.run_until_sample(3500);
  const uint64_t req_cycle = b.cycle();
  b.send(enc.request_status());
  b.run_until_sample(n + 63);
  expect_clean_run(b);

  ASSERT_GT(b.mask_change_cycle, 0u);
  const uint64_t quiet_from = b.mask_change_cycle + 2 * decim * kPeriod;
  int spikes_after = 0, spikes_after_bad = 0;
  for (const auto& r : b.received()) {
    if (r.start_cycle < quiet_from) continue;
    EXPECT_TRUE(r.p.type == eskin::link::kSpikes || r.p.type == eskin::link::kStatus)
        << "packet type " << int(r.p.type) << " at cycle " << r.start_cycle;
    if (r.p.type == eskin::link::kSpikes) ++spikes_after;
    if (r.p.type == eskin::link::kSpikes && r.p.t > 3100) ++spikes_after_bad;
  }
  EXPECT_GE(spikes_after, 10);
  EXPECT_GE(spikes_after_bad, 5);  // the data path runs on after the bad frame
  expect_same_packets(want, keys(b.received()), uint32_t(n) - decim, decim,
                      {eskin::link::kSpikes}, 20);

  const Received* st = nullptr;
  for (const auto& r : b.received())
    if (r.p.type == eskin::link::kStatus && r.start_cycle > req_cycle) { st = &r; break; }
  ASSERT_NE(st, nullptr) << "no status packet after REQUEST_STATUS";
  EXPECT_EQ(st->p.status.cmd_crc_errors + st->p.status.cmd_frame_errors, 1);
  EXPECT_EQ(st->p.status.cmd_accepted, 2);  // the mask and the status request
  EXPECT_EQ(st->p.status.cmd_rejected, 0);
  EXPECT_EQ(st->p.status.output_mask, eskin::hls::kMaskSpikes);
  EXPECT_EQ(st->p.status.adc_overruns, 0);
  EXPECT_EQ(st->p.status.dropped_frames, 0);
  EXPECT_EQ(st->p.status.uart_rx_errors, 0);
  EXPECT_GE(st->p.status.samples, 3500u);
  EXPECT_LE(st->p.status.samples, 3502u);  // sent within ~2 samples of the request
}

// A 16x16 skin: 32 carriers planned on DFT bins (carriers: auto, window
// 128), one press. Matches the 16x16 build (tests/rtl/dtmf_top_test.cmake).
const eskin::sim::Scene& skin16_scene() {
  static const auto sc = eskin::sim::parse_scene(R"(
name: skin16
seed: 3
duration_s: 0.12
skin:
  rows: 16
  cols: 16
  carriers: auto
  osc_amplitude_v: 1.0
  amp_gain: 0.5
  conductance: {kind: saturating, p_half_kpa: 50}
  adc: {rate_hz: 35000, bits: 10, full_scale_v: 3.3, offset_v: 1.65, noise_rms_v: 0.001}
decoder: {window: 128, variant: exact}
neuron: {preset: RA, input: level, input_scale: 10}
stimuli:
  - press: {taxel: [3, 12], pressure_kpa: 60, t_start_s: 0.010, ramp_s: 0.005, hold_s: 0.060, release_s: 0.005}
outputs: [amplitudes, taxels, spikes]
)", "skin16 (dtmf_top_test)");
  return sc;
}
constexpr int kStep16 = 16;
constexpr uint16_t kDecim16 = 8;

// Bound: exact equality, as for the default scene; the 16x16 build runs the
// stages every 16 samples (dt = 16/35 ms) and must still lose no sample.
TEST(DtmfTop, Skin16x16MatchesHlsChainAndKeepsUp) {
  const auto& scene = skin16_scene();
  ASSERT_EQ(scene.skin.carriers(), 32);
  auto codes = scene_codes12(scene);
  const size_t n = codes.size();
  codes.resize(n + 160, 2048);
  auto chain = std::make_unique<Chain16>(chain_config<Chain16>(scene, kStep16, kDecim16, 7));
  ASSERT_TRUE(chain->ok());
  const auto want = run_chain(*chain, codes, n);
  Board<Vdtmf_top_s16> b(codes);
  b.run_until_sample(n + 159);
  expect_clean_run(b);
  expect_same_packets(want, keys(b.received()), uint32_t(n) - kStep16 * kDecim16,
                      kStep16 * kDecim16, kDataTypes, 3);
}

// Latency of one frame through the pipeline, in clock cycles (12 MHz) from
// the 16th SCLK falling edge of sample n (the edge that clocks in DB0; CS
// rises one half SCLK period later), to the cycle in which each handshake
// happens.
struct Latency {
  int64_t adc, sd_first, sd_last, mg_first, mg_last, tx_first, tx_last, nr_first, nr_last,
      hdr_amp, uart_amp, hdr_tax, uart_tax;
};

template <class M>
Latency measure(Board<M>& b, uint32_t n) {
  const auto& e = b.events.at(n);
  const int64_t ref = int64_t(b.sample_edge(n));
  const auto start_of = [&](uint8_t type) -> int64_t {
    for (const auto& r : b.received())
      if (r.p.type == type && r.p.t == n) return int64_t(r.start_cycle) - ref;
    ADD_FAILURE() << "no packet of type " << int(type) << " for sample " << n;
    return -1;
  };
  const auto hdr_of = [&](uint8_t type) -> int64_t {
    const auto it = e.hdr.find(type);
    if (it == e.hdr.end()) return -1;
    return int64_t(it->second) - ref;
  };
  return Latency{int64_t(e.adc) - ref, int64_t(e.sd_first) - ref, int64_t(e.sd_last) - ref,
                 int64_t(e.mg_first) - ref, int64_t(e.mg_last) - ref, int64_t(e.tx_first) - ref,
                 int64_t(e.tx_last) - ref, int64_t(e.nr_first) - ref, int64_t(e.nr_last) - ref,
                 hdr_of(eskin::link::kAmplitudes), start_of(eskin::link::kAmplitudes),
                 hdr_of(eskin::link::kTaxelsDense), start_of(eskin::link::kTaxelsDense)};
}

// The stage latencies follow from each module's documented schedule
// (headers of rtl/*.v), for K carriers and T taxels with nothing stalled
// downstream except by the next stage's own pace:
//   adc_ad7476: m_valid on the 16th SCLK falling edge             -> 0
//   sdft_bank: token k valid 8 + 6 k cycles after the sample handshake
//   without a frame buffer carrier_magnitude (II 26) paces the tokens:
//     token k is taken at 8 + 26 k; with token_fifo (16x16) the DFT runs at
//     its own pace (8 + 6 k) and the magnitude unit sees token 0 at 8 + 3
//   carrier_magnitude: out 25 cycles after its input (NB + 8, MAG_W 16),
//     inputs 26 cycles apart
//   taxel_reconstruct (conductance, c = MAG_W + 2 = 18 cycles per taxel):
//     taxel i leaves at last_in + 1 + (i + 1) c
//   izhikevich_layer: out 11 cycles after its input (II 12 < 18: no stall)
//   frame_packetizer: link_framer header 2 cycles after the last magnitude
// The tail (link_framer collects the first COBS block before its code byte
// goes out, which depends on the t and seq bytes; uart_tx starts the bit
// the cycle after the byte handshake; a taxel packet also waits for the
// amplitude packet ahead of it) is pinned at the measured figures.
Latency expected_core(int K, int T, bool fifo) {
  Latency l{};
  l.adc = 0;
  l.sd_first = 8;
  const int64_t mag_in0 = fifo ? 8 + 3 : 8;
  l.sd_last = fifo ? 8 + 6 * (K - 1) : 8 + 26 * (K - 1);
  l.mg_first = mag_in0 + 25;
  l.mg_last = mag_in0 + 26 * (K - 1) + 25;
  l.tx_first = l.mg_last + 1 + 18;
  l.tx_last = l.mg_last + 1 + int64_t(T) * 18;
  l.nr_first = l.tx_first + 11;
  l.nr_last = l.tx_last + 11;
  l.hdr_amp = l.mg_last + 2;
  return l;
}

void print_table(const Latency& a, const Latency& b) {
  const auto row = [](const char* name, int64_t x, int64_t y) {
    std::printf("  %-44s %8lld %10lld\n", name, (long long)x, (long long)y);
  };
  std::printf("Pipeline latency, cycles at 12 MHz from the 16th SCLK falling edge of sample n\n");
  std::printf("  %-44s %8s %10s\n", "event", "3x3", "16x16");
  row("ADC token into sdft_bank", a.adc, b.adc);
  row("sdft_bank first token (k = 0)", a.sd_first, b.sd_first);
  row("sdft_bank last token (k = K-1)", a.sd_last, b.sd_last);
  row("carrier_magnitude first magnitude", a.mg_first, b.mg_first);
  row("carrier_magnitude last magnitude", a.mg_last, b.mg_last);
  row("taxel_reconstruct first taxel", a.tx_first, b.tx_first);
  row("taxel_reconstruct last taxel", a.tx_last, b.tx_last);
  row("izhikevich_layer first neuron (spike flag)", a.nr_first, b.nr_first);
  row("izhikevich_layer last neuron (step done)", a.nr_last, b.nr_last);
  row("link_framer header, amplitude packet", a.hdr_amp, b.hdr_amp);
  row("UART first start bit, amplitude packet", a.uart_amp, b.uart_amp);
  row("link_framer header, taxel packet", a.hdr_tax, b.hdr_tax);
  row("UART first start bit, taxel packet", a.uart_tax, b.uart_tax);
}

void expect_core(const Latency& got, const Latency& want, const char* what) {
  EXPECT_EQ(got.adc, want.adc) << what;
  EXPECT_EQ(got.sd_first, want.sd_first) << what;
  EXPECT_EQ(got.sd_last, want.sd_last) << what;
  EXPECT_EQ(got.mg_first, want.mg_first) << what;
  EXPECT_EQ(got.mg_last, want.mg_last) << what;
  EXPECT_EQ(got.tx_first, want.tx_first) << what;
  EXPECT_EQ(got.tx_last, want.tx_last) << what;
  EXPECT_EQ(got.nr_first, want.nr_first) << what;
  EXPECT_EQ(got.nr_last, want.nr_last) << what;
  EXPECT_EQ(got.hdr_amp, want.hdr_amp) << what;
}

// Sample n is a packet step with the link idle (no press yet: no spikes;
// earlier packets long sent), so the figures are the pipeline's own.
TEST(DtmfTop, LatencyTable) {
  auto c3 = scene_codes12(default_scene());
  const uint32_t n3 = 70;  // step 70: amplitude and taxel packets (35 | 70)
  Board<Vdtmf_top> b3(c3);
  b3.run_until_sample(n3 + 12);
  const Latency l3 = measure(b3, n3);

  auto c16 = scene_codes12(skin16_scene());
  const uint32_t n16 = 256;  // step 16: packets every 8 steps (8 | 16)
  Board<Vdtmf_top_s16> b16(c16);
  b16.run_until_sample(n16 + 100);
  const Latency l16 = measure(b16, n16);

  print_table(l3, l16);
  expect_core(l3, expected_core(6, 9, false), "3x3");
  expect_core(l16, expected_core(32, 256, true), "16x16");
  // Measured tails (see above), pinned.
  EXPECT_EQ(l3.uart_amp, 172);
  EXPECT_EQ(l3.hdr_tax, 855);
  EXPECT_EQ(l3.uart_tax, 1132);
  EXPECT_EQ(l16.uart_amp, 850);
  EXPECT_EQ(l16.hdr_tax, 5453);
  EXPECT_EQ(l16.uart_tax, 5459);
  // Both must fit their step: a frame's last neuron update ends before the
  // next step's sample arrives (else the ADC would overrun).
  EXPECT_LT(l3.nr_last, 1 * kPeriod);
  EXPECT_LT(l16.tx_last, kStep16 * kPeriod);
  RecordProperty("latency_3x3_to_amplitude_start_bit", int(l3.uart_amp));
  RecordProperty("latency_3x3_to_taxel_start_bit", int(l3.uart_tax));
  RecordProperty("latency_16x16_to_amplitude_start_bit", int(l16.uart_amp));
  RecordProperty("latency_16x16_to_taxel_start_bit", int(l16.uart_tax));
  std::printf("Cycle budget per step: 3x3 %d cycles per sample, busiest stage carrier_magnitude "
              "%lld (6 x 26), whole frame %lld; 16x16 %d cycles per step (16 samples), busiest "
              "taxel_reconstruct %lld (256 x 18 + 33)\n",
              kPeriod, (long long)(l3.mg_last - l3.sd_first), (long long)l3.nr_last,
              kStep16 * kPeriod, (long long)(l16.tx_last - l16.mg_last + 33));
}

// SET_CARRIER_INC (build with CARRIER_CMD = 1): the new carrier table is
// written to sdft_bank, which clears its window, phases and sums, and
// applies from the first sample it accepts after the write (sample s, read
// from the probes). Bound: exact equality with the chain that calls
// set_carriers() before sample s, for every packet before and after.
TEST(DtmfTop, CarrierCommandReloadsTheDft) {
  const auto& scene = default_scene();
  auto codes = scene_codes12(scene);
  const size_t n = 6000;
  codes.resize(n + 64);
  const uint16_t decim = 35;
  auto cfg = chain_config<Chain3>(scene, 1, decim, 7);
  const uint32_t new_inc = eskin::hls::sdft_phase_increment(2200.0, scene.skin.adc.rate_hz);
  ASSERT_NE(new_inc, cfg.sdft.inc[0]);

  Board<Vdtmf_top_cc> b(codes);
  eskin::link::LinkEncoder enc;
  b.run_until_sample(1500);
  const size_t loads_before = b.carrier_loads.size();
  b.send(enc.set_carrier_inc(0, new_inc));
  b.run_until_sample(n + 63);
  expect_clean_run(b);
  ASSERT_EQ(b.carrier_loads.size(), loads_before + 1) << "one reload";
  const uint64_t load = b.carrier_loads.back();
  uint32_t s = 0;
  for (const auto& [t, e] : b.events)
    if (e.adc > load) { s = t; break; }
  ASSERT_GT(s, 1500u);
  ASSERT_LT(s, 1600u);

  Chain3 chain(cfg);
  auto want = run_chain(chain, codes, s);
  auto next = cfg.sdft;
  next.inc[0] = new_inc;
  ASSERT_TRUE(chain.set_carriers(next));
  // Continue the same chain from sample s.
  {
    std::vector<uint16_t> tail(codes.begin() + s, codes.begin() + long(n));
    auto pk = std::make_unique<Chain3::Packet[]>(3);
    Chain3::Packet(&p3)[3] = *reinterpret_cast<Chain3::Packet(*)[3]>(pk.get());
    for (size_t i = 0; i < tail.size(); ++i) {
      const int np = chain.push(tail[i], uint32_t(s + i), p3);
      for (int j = 0; j < np; ++j)
        want.push_back({p3[j].type, p3[j].t, {p3[j].payload, p3[j].payload + p3[j].len}});
    }
  }
  expect_same_packets(want, keys(b.received()), uint32_t(n) - decim, decim, kDataTypes, 3);
  // The carrier really changed: amplitude 0 after the reload differs from
  // what the old table gives on the same samples.
  Chain3 old(cfg);
  const auto old_pk = run_chain(old, codes, n);
  int differ = 0;
  const auto a_new = of_type(want, eskin::link::kAmplitudes, uint32_t(n), decim);
  const auto a_old = of_type(old_pk, eskin::link::kAmplitudes, uint32_t(n), decim);
  for (size_t i = 0; i < a_new.size() && i < a_old.size(); ++i)
    if (a_new[i].t > s && !(a_new[i] == a_old[i])) ++differ;
  EXPECT_GT(differ, 10);
}

}  // namespace
