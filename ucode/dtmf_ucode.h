// Host-side: the DTMF microprogram (rtl/ucode/dtmf_chain.fe, built into the
// binary) assembled for a plan's engine image, and the $readmemh files the
// top reads (UCODE_HEX, KROM_HEX). Every build of rtl/dtmf_top.v — the
// tests, the virtual board, `eskin bitstream` — takes its microcode and
// constants from here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ucode/dtmf_engine_image.h"
#include "ucode/frame_engine_asm.h"

namespace eskin::hls {

// The microprogram's source text (rtl/ucode/dtmf_chain.fe at build time).
const std::string& dtmf_ucode_source();

// Assembles it with the image's symbols; throws fe_asm::AsmError naming the
// line on an error (e.g. a program larger than kDtmfImemWords).
std::vector<uint32_t> dtmf_ucode_words(const EngineImage& image);
// The same, whole: words, symbols, listing and .bound annotations.
fe_asm::Program dtmf_ucode_program(const EngineImage& image);

// The routine each microcode word belongs to: the program's sections, each
// opened by a `; ==== NAME ==` line and named after the HLS kernel it
// implements (carrier_demix, izhikevich_layer, ...) or its part of the
// program (boot, main, packets, commands). Index = IMEM address.
std::vector<std::string> dtmf_ucode_routines(const EngineImage& image);

// The files a build of the top needs, written into `dir` as
// NAME.ucode.hex and NAME.krom.hex; returns dtmf_top's parameters (paths
// absolute when `dir` is). Throws std::runtime_error naming a file it could
// not write.
std::vector<VerilogParam> write_dtmf_top_build(const DtmfTopPlan& plan, const std::string& dir,
                                               const std::string& name);

}  // namespace eskin::hls
