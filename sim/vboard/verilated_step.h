// Verilator's SystemC model evaluates itself in an SC_METHOD sensitive to
// its input ports, i.e. one SystemC delta cycle per clock edge, which costs
// more than the evaluation (docs/vboard.md). The board clocks it directly
// instead, through the model's own eval_step(), which Verilator declares
// private. An explicit instantiation may name a private member (C++17
// [temp.explicit]/14): ESKIN_EXPOSE_EVAL_STEP(Vtop) instantiates a template
// with &Vtop::eval_step, whose friend eval_step_of(Vtop*) hands it out.
// Use at namespace scope, once per model class:
//   ESKIN_EXPOSE_EVAL_STEP(Vhall_top)
//   (top.*eval_step_of(&top))();
#pragma once

#define ESKIN_EXPOSE_EVAL_STEP(V)                          \
  using V##_eval_step = void (V::*)();                     \
  V##_eval_step eval_step_of(V*);                          \
  template <V##_eval_step M>                               \
  struct V##_expose_eval_step {                            \
    friend V##_eval_step eval_step_of(V*) { return M; }    \
  };                                                       \
  template struct V##_expose_eval_step<&V::eval_step>;
