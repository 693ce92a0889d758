// The generated core modules a build puts into its board wrapper
// (rtl/board_*.v, macros ESKIN_DTMF_CORE / ESKIN_HALL_CORE): Yosys takes no
// -G of packed vectors (a scene's hall_top addresses, mux channels, range
// ends), so a module instantiates the top with the scene's parameters.
//   dtmf_top: its ports as they are (the board wrapper ties the packet
//     stream off, as it does for dtmf_top itself).
//   hall_top: its ports but the packet stream (EXT_LINK 0: it owns the link;
//     pkt_ready tied low, pkt_valid / pkt_data left open).
//   mixed_top: its ports as they are.
#pragma once

#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"

namespace eskin::fpga {

// "-GNAME=VALUE" (Verilator's form, as sim/ derives them) -> {NAME, VALUE};
// throws std::invalid_argument on anything else.
std::vector<hls::VerilogParam> from_g_args(const std::vector<std::string>& g_args);

std::string dtmf_core_wrapper(const std::string& name,
                              const std::vector<hls::VerilogParam>& params);
std::string hall_core_wrapper(const std::string& name, int nb, int nsb,
                              const std::vector<hls::VerilogParam>& params);
std::string mixed_core_wrapper(const std::string& name, int nb, int nsb,
                               const std::vector<hls::VerilogParam>& params);

}  // namespace eskin::fpga
