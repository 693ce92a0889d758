// Explicit instantiations for the hls/ purity check (tests/hls/hls_purity_test.cpp).
//
// Convention: a kernel template emits code only when instantiated, so each
// kernel header gets a block here that instantiates it at its default (or
// typical) parameters. Each block is guarded by __has_include, so a renamed
// or not-yet-committed header never breaks the check. The generated unit
// (hls/CMakeLists.txt) includes every hls/*.h except the host-side
// *_config.h builders, then this file.
// A header with no block here is still covered: it is compiled in the unit
// (syntax, -fno-exceptions, -fno-rtti), its non-template inline functions are
// emitted and disassembled (-fkeep-inline-functions pass), and its source is
// scanned for float/heap/exception/RTTI tokens. The test prints which headers
// lack a block: add one when you add a kernel.
#pragma once

#if __has_include("hls/carrier_magnitude.h")
#include "hls/carrier_magnitude.h"
template struct eskin::hls::CarrierMagnitude<24, 16, 8>;
template struct eskin::hls::CarrierMagnitude<13, 8, 0>;
#endif

#if __has_include("hls/sdft_bank.h")
#include "hls/sdft_bank.h"
template class eskin::hls::SdftBank<6, 32>;
template struct eskin::hls::SdftBankConfig<6>;
#endif

#if __has_include("hls/isqrt.h")
#include "hls/isqrt.h"
template struct eskin::hls::IsqrtState<16>;
template uint32_t eskin::hls::isqrt<16>(uint32_t);
#endif

#if __has_include("hls/taxel_reconstruct.h")
#include "hls/taxel_reconstruct.h"
template class eskin::hls::TaxelReconstruct<3, 3>;
template class eskin::hls::TaxelReconstructStream<3, 3>;
#endif

#if __has_include("hls/izhikevich_layer.h")
#include "hls/izhikevich_layer.h"
template class eskin::hls::IzhikevichLayer<9>;
#endif

#if __has_include("hls/ghost_filter.h")
#include "hls/ghost_filter.h"
template class eskin::hls::GhostFilter<3, 3, 4>;
#endif

#if __has_include("hls/sdft_damped.h")
#include "hls/sdft_damped.h"
template class eskin::hls::GoertzelBlockBank<6, 32>;
#endif

#if __has_include("hls/spike_encoder.h")
#include "hls/spike_encoder.h"
template class eskin::hls::SpikeEncoder<256>;
#endif

#if __has_include("hls/synapse_weights.h")
#include "hls/synapse_weights.h"
template class eskin::hls::SynapseWeights<3, 3>;
#endif

#if __has_include("hls/dtmf_chain.h")
#include "hls/dtmf_chain.h"
template class eskin::hls::DtmfChain<eskin::hls::DtmfChainSizes<3, 3, 32>>;
#endif

#if __has_include("hls/carrier_demix.h")
#include "hls/carrier_demix.h"
template class eskin::hls::CarrierDemix<6, 32>;
template struct eskin::hls::CarrierDemixConfig<6>;
#endif

#if __has_include("ucode/frame_engine.h")
#include "ucode/frame_engine.h"
template class eskin::hls::FrameEngine<>;
template uint32_t eskin::hls::FrameEngine<>::step<eskin::hls::FrameEngineNullIo>(
    eskin::hls::FrameEngineNullIo&, uint64_t);
template uint64_t eskin::hls::FrameEngine<>::run<eskin::hls::FrameEngineNullIo>(
    eskin::hls::FrameEngineNullIo&, uint64_t);
#endif

#if __has_include("hls/hall_baseline.h")
#include "hls/hall_baseline.h"
template class eskin::hls::HallBaseline<16, 4>;
#endif

#if __has_include("hls/ft_calibrate.h")
#include "hls/ft_calibrate.h"
template class eskin::hls::FtCalibrate<16>;
#endif

#if __has_include("hls/force_curve.h")
#include "hls/force_curve.h"
template class eskin::hls::ForceCurve<9, 13, 3>;
#endif

#if __has_include("hls/hall_decouple.h")
#include "hls/hall_decouple.h"
template class eskin::hls::HallDecouple<0>;
#endif

#if __has_include("hls/taxel_packetizer.h")
#include "hls/taxel_packetizer.h"
namespace eskin::hls::purity {
struct TaxelPacket3x3 {
  uint8_t type;
  uint32_t t;
  uint16_t len;
  uint8_t payload[36];
};
}  // namespace eskin::hls::purity
template struct eskin::hls::TaxelPacketizer<3, 3>;
template int eskin::hls::TaxelPacketizer<3, 3>::frame(const uint16_t*, uint32_t, bool, bool,
                                                      uint16_t,
                                                      eskin::hls::purity::TaxelPacket3x3*);
#endif
