#include "sim/mlx90393_model.h"

#include <cmath>
#include <cstdlib>

namespace eskin::sim {

namespace mlx = eskin::mlx90393;

Mlx90393Model::Mlx90393Model(I2cBus& bus, const HallFieldSource& field, int sensor,
                             Mlx90393Options opt, int segment)
    : I2cTarget(bus, "MLX90393#" + std::to_string(sensor),
                mlx::address(opt.a1, opt.a0, opt.base_address), segment, opt.t_out_ns),
      field_(field),
      sensor_(sensor),
      opt_(opt),
      rng_(opt.seed) {
  mlx::validate(opt.config, "mlx90393[" + std::to_string(sensor) + "]");
  nv_[0] = opt.config.reg0();
  nv_[1] = opt.config.reg1();
  nv_[2] = opt.config.reg2();
  regs_ = nv_;
  regs_[mlx::kRegTref] = opt.tref;
}

uint8_t Mlx90393Model::status(bool error, int data_bytes) {
  uint8_t s = mlx::d_field(data_bytes);
  if (mode_ == Mode::Burst) s |= mlx::kStatusBurst;
  if (mode_ == Mode::Woc) s |= mlx::kStatusWoc;
  if (mode_ == Mode::Single) s |= mlx::kStatusSm;
  if (error) {
    s |= mlx::kStatusError;
    ++error_replies_;
  }
  if (rs_) s |= mlx::kStatusRs;
  return s;
}

void Mlx90393Model::start_conversion(double t) {
  conv_start_ = t;
  conv_done_ = t + 1000.0 * mlx::conversion_us(config(), sel_);
  converting_ = true;
}

void Mlx90393Model::complete_conversion() {
  const mlx::Config c = config();
  const int m = mlx::value_count(sel_ & mlx::kXYZ);
  const double t_mid_ns =
      conv_start_ + 1000.0 * (mlx::kTstbyUs + mlx::kTactiveUs + 0.5 * m * mlx::tconvm_us(c.osr, c.dig_filt));
  const std::array<double, 3> b = field_.field_uT(sensor_, t_mid_ns * 1e-9);
  Measurement r{};
  r.t_done_ns = conv_done_;
  r.zyxt = sel_;
  uint16_t* out[3] = {&r.x, &r.y, &r.z};
  std::array<int, 3> lsb{};
  for (int a = 0; a < 3; ++a) {
    if (!(sel_ & (mlx::kX << a))) continue;
    std::normal_distribution<double> noise(0.0, opt_.noise_rms_uT[a]);
    const double v = b[a] + opt_.offset_uT[a] + (opt_.noise_rms_uT[a] > 0 ? noise(rng_) : 0.0);
    const mlx::Code code = mlx::encode_uT(c, a, v);
    *out[a] = code.code;
    r.saturated[a] = code.saturated;
    lsb[a] = mlx::code_to_lsb(c, a, code.code);
  }
  if (sel_ & mlx::kT) r.t = mlx::temperature_code(opt_.temperature_c, opt_.tref);
  done_.push_back(r);

  bool report = true;
  if (mode_ == Mode::Woc) {  // wake-up on change: only a large enough change reports
    const int thr[3] = {int(regs_[mlx::kRegWoxyThreshold]), int(regs_[mlx::kRegWoxyThreshold]),
                        int(regs_[mlx::kRegWozThreshold])};
    report = false;
    if (woc_have_ref_)
      for (int a = 0; a < 3; ++a)
        if ((sel_ & (mlx::kX << a)) && std::abs(lsb[a] - woc_ref_[a]) > thr[a]) report = true;
    if (!woc_have_ref_ || c.woc_diff) woc_ref_ = lsb;
    woc_have_ref_ = true;
  }
  if (report) {
    last_ = r;
    data_ready_ = true;
    drdy_ = true;
  }
}

void Mlx90393Model::advance(double t) {
  while (converting_ && conv_done_ <= t) {
    converting_ = false;
    complete_conversion();
    if (mode_ == Mode::Single) {
      mode_ = Mode::Idle;
    } else if (mode_ == Mode::Burst || mode_ == Mode::Woc) {
      const double next = conv_start_ + 1000.0 * mlx::burst_period_us(config(), sel_);
      start_conversion(next);
    }
  }
}

bool Mlx90393Model::address_match(double t, bool read) {
  advance(t);
  if (read) rpos_ = 0;
  else ncmd_ = 0;
  return true;
}

namespace {
int command_length(uint8_t first) {
  const uint8_t op = first & 0xF0;
  return op == mlx::kRR ? 2 : op == mlx::kWR ? 4 : 1;
}
}  // namespace

bool Mlx90393Model::write_byte(double t, uint8_t b) {
  if (ncmd_ > 0 && ncmd_ >= command_length(cmd_[0])) return false;  // NACK extra bytes
  cmd_[ncmd_++] = b;
  if (ncmd_ == command_length(cmd_[0])) execute(t);
  return true;
}

uint8_t Mlx90393Model::read_byte(double /*t*/) {
  return rpos_ < nreply_ ? reply_[rpos_++] : 0x00;
}

void Mlx90393Model::transaction_end(double /*t*/, bool /*repeated_start*/) {
  if (ncmd_ > 0 && ncmd_ < command_length(cmd_[0])) reply_status(true);  // command cut short
  ncmd_ = 0;
}

void Mlx90393Model::execute(double t) {
  advance(t);
  ++commands_;
  const uint8_t op = cmd_[0] & 0xF0, zyxt = cmd_[0] & 0x0F;
  rs_ = false;
  switch (op) {
    case mlx::kNOP: reply_status(cmd_[0] != 0); break;
    case mlx::kSB:
    case mlx::kSW:
    case mlx::kSM: {
      const uint8_t sel = zyxt ? zyxt : (op == mlx::kSM ? 0 : uint8_t(config().burst_sel));
      if (mode_ != Mode::Idle || sel == 0) {
        reply_status(true);
        break;
      }
      mode_ = op == mlx::kSB ? Mode::Burst : op == mlx::kSW ? Mode::Woc : Mode::Single;
      sel_ = sel;
      woc_have_ref_ = false;
      start_conversion(t);
      reply_status(false);
      break;
    }
    case mlx::kRM: {
      const int n = mlx::value_count(zyxt);
      bool error = !data_ready_ || n == 0 || (zyxt & ~last_.zyxt) != 0;
      if (inject_error_ > 0) {
        --inject_error_;
        error = true;
      }
      int k = 1;
      const uint16_t vals[4] = {last_.t, last_.x, last_.y, last_.z};
      for (int a = 0; a < 4; ++a)
        if (zyxt & (1 << a)) {
          reply_[k++] = uint8_t(vals[a] >> 8);
          reply_[k++] = uint8_t(vals[a]);
        }
      int d_bytes = 2 * n;
      if (inject_count_ > 0) {
        --inject_count_;
        d_bytes = d_bytes >= 4 ? d_bytes - 2 : d_bytes + 2;
      }
      reply_[0] = status(error, d_bytes);
      nreply_ = k;
      if (!error) {
        Measurement d = last_;
        d.zyxt = zyxt;
        delivered_.push_back(d);
      }
      data_ready_ = false;
      drdy_ = false;
      break;
    }
    case mlx::kRR: {
      const int a = cmd_[1] >> 2;
      reply_[0] = status(false, 2);
      reply_[1] = uint8_t(regs_[a] >> 8);
      reply_[2] = uint8_t(regs_[a]);
      nreply_ = 3;
      break;
    }
    case mlx::kWR: {
      const int a = cmd_[3] >> 2;
      const uint16_t v = uint16_t(cmd_[1] << 8 | cmd_[2]);
      bool ok = a <= mlx::kUserRegisterLast;
      if (ok && a <= 2) {
        uint16_t r[3] = {regs_[0], regs_[1], regs_[2]};
        r[a] = v;
        ok = mlx::illegal_reason(mlx::Config::from_registers(r[0], r[1], r[2])).empty();
      }
      if (ok) regs_[a] = v;
      reply_status(!ok);
      break;
    }
    case mlx::kEX:
      mode_ = Mode::Idle;
      converting_ = false;
      reply_status(false);
      break;
    case mlx::kHR:
      for (int a = 0; a <= mlx::kUserRegisterLast; ++a) regs_[a] = nv_[a];
      reply_status(false);
      break;
    case mlx::kHS:
      for (int a = 0; a <= mlx::kUserRegisterLast; ++a) nv_[a] = regs_[a];
      reply_status(false);
      break;
    case mlx::kRT:
      for (int a = 0; a <= mlx::kUserRegisterLast; ++a) regs_[a] = nv_[a];
      mode_ = Mode::Idle;
      converting_ = data_ready_ = drdy_ = false;
      rs_ = true;
      reply_status(false);
      break;
    default: reply_status(true); break;
  }
}

}  // namespace eskin::sim
