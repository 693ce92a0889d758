// The generated core modules a Hall or mixed build puts into its board
// wrapper (rtl/board_*_hall.v, macro ESKIN_HALL_CORE), as
// hls::dtmf_top_wrapper does for the DTMF top: Yosys takes no -G of the
// packed vectors (addresses, mux channels, range ends) a scene's hall_top
// needs, so a module instantiates the top with them.
//   hall_top: its ports but the packet stream (EXT_LINK 0: it owns the link;
//     pkt_ready tied low, pkt_valid / pkt_data left open).
//   mixed_top: its ports as they are.
#pragma once

#include <string>
#include <vector>

#include "hls/dtmf_top_config.h"

namespace eskin::fpga {

// "-GNAME=VALUE" (Verilator's form, as sim/ derives them) -> {NAME, VALUE};
// throws std::invalid_argument on anything else.
std::vector<hls::VerilogParam> from_g_args(const std::vector<std::string>& g_args);

std::string hall_core_wrapper(const std::string& name, int nb, int nsb,
                              const std::vector<hls::VerilogParam>& params);
std::string mixed_core_wrapper(const std::string& name, int nb, int nsb,
                               const std::vector<hls::VerilogParam>& params);

}  // namespace eskin::fpga
