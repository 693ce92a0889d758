// What both board executables do around their Verilated SystemC model V
// (vboard_main.cpp: dtmf_top, vboard_hall_main.cpp: hall_top): the clock
// pin, one clock cycle as two evaluations through V's eval_step()
// (verilated_step.h: ESKIN_EXPOSE_EVAL_STEP(V) must precede the use), and
// the FST trace. A board binds its other ports, writes its inputs, calls
// clock() and reads its outputs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <vector>

#include "sim/vboard/direct_wire.h"
#include "sim/vboard/fpga_model.h"
#include "sim/vboard/fpga_params.h"
#include "verilated.h"
#include "verilated_fst_c.h"

namespace eskin::vboard {

// Gives the model this run's microcode files (RunFiles::plusargs) before its
// first evaluation reads them.
inline void add_plusargs(const RunFiles& files) {
  const std::vector<std::string> args = files.plusargs();
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  Verilated::commandArgsAdd(int(argv.size()), argv.data());
}

template <class V>
class VerilatedTop : public FpgaModel {
 public:
  ~VerilatedTop() override { close_trace(); }
  void open_trace(const std::string& path) override {
    Verilated::traceEverOn(true);
    fst_ = std::make_unique<VerilatedFstC>();
    top_.trace(fst_.get(), 99);
    fst_->open(path.c_str());
  }
  void close_trace() override {
    if (fst_) fst_->close();
    fst_.reset();
  }
  void set_half_period_ps(uint64_t h) { half_ps_ = h; }

 protected:
  VerilatedTop() : clk_("clk"), top_("fpga") { top_.clk(clk_); }
  // The rising edge at t_ps (inputs as written before), then the falling
  // edge half a period later; each dumped when tracing.
  void clock(uint64_t t_ps) {
    clk_.write(true);
    (top_.*eval_)();
    if (fst_) fst_->dump(t_ps);
    clk_.write(false);
    (top_.*eval_)();
    if (fst_) fst_->dump(t_ps + half_ps_);
  }

  DirectWire clk_;
  V top_;

 private:
  void (V::*eval_)() = eval_step_of(&top_);
  std::unique_ptr<VerilatedFstC> fst_;
  uint64_t half_ps_ = 0;
};

}  // namespace eskin::vboard
