#include "ghost_filter.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "eskin/skin_config.h"

namespace eskin::golden {
namespace {

// Ridge weight of the joint solve: big enough to make a rank-deficient site
// set (a rectangle) well posed, small enough (relative bias ~1e-12) not to
// matter for decodable patterns.
constexpr double kRidge = 1e-12;
constexpr int kMaxEnumerated = 16;  // crossings enumerated exhaustively (2^16 sets)

std::string num(double v) { return std::to_string(v); }

// Columns of the line-incidence matrix: site s = (r, c) adds its value to
// line r (a row) and to line rows + c (a column).
Eigen::MatrixXd incidence(const std::vector<std::pair<int, int>>& sites, int rows, int lines) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(lines, Eigen::Index(sites.size()));
  for (size_t s = 0; s < sites.size(); ++s) {
    A(sites[s].first, Eigen::Index(s)) = 1.0;
    A(rows + sites[s].second, Eigen::Index(s)) = 1.0;
  }
  return A;
}

}  // namespace

Eigen::VectorXd nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int n = int(A.cols());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  if (n == 0) return x;
  const double tol = 1e-13 * std::max(1.0, A.norm() * b.norm());
  std::vector<bool> passive(size_t(n), false);
  const int max_iter = 3 * n + 10;
  for (int outer = 0; outer < max_iter; ++outer) {
    Eigen::VectorXd w = A.transpose() * (b - A * x);
    int t = -1;
    double wmax = tol;
    for (int j = 0; j < n; ++j)
      if (!passive[size_t(j)] && w[j] > wmax) wmax = w[j], t = j;
    if (t < 0) break;  // KKT: no inactive variable would lower the residual
    passive[size_t(t)] = true;
    for (int inner = 0; inner < max_iter; ++inner) {
      std::vector<int> P;
      for (int j = 0; j < n; ++j)
        if (passive[size_t(j)]) P.push_back(j);
      Eigen::MatrixXd Ap(A.rows(), Eigen::Index(P.size()));
      for (size_t k = 0; k < P.size(); ++k) Ap.col(Eigen::Index(k)) = A.col(P[k]);
      Eigen::VectorXd zp = Ap.colPivHouseholderQr().solve(b);
      if ((zp.array() > 0.0).all()) {
        x.setZero();
        for (size_t k = 0; k < P.size(); ++k) x[P[k]] = zp[Eigen::Index(k)];
        break;
      }
      // Step from x towards z until the first passive variable hits zero.
      double alpha = 1.0;
      int hit = -1;
      for (size_t k = 0; k < P.size(); ++k) {
        double z = zp[Eigen::Index(k)], xj = x[P[k]];
        if (z <= 0.0) {
          double a = xj / (xj - z);
          if (a < alpha) alpha = a, hit = P[k];
        }
      }
      for (size_t k = 0; k < P.size(); ++k)
        x[P[k]] += alpha * (zp[Eigen::Index(k)] - x[P[k]]);
      if (hit >= 0) x[hit] = 0.0;
      for (int j : P)
        if (x[j] <= 0.0) x[j] = 0.0, passive[size_t(j)] = false;
    }
  }
  return x;
}

GhostFilter::GhostFilter(int rows, int cols, GhostFilterConfig cfg)
    : rows_(rows), cols_(cols), cfg_(cfg) {
  if (rows < 1) throw ConfigError("ghost_filter.rows", "expected >= 1, got " + std::to_string(rows));
  if (cols < 1) throw ConfigError("ghost_filter.cols", "expected >= 1, got " + std::to_string(cols));
  if (cfg.lookback < 1)
    throw ConfigError("ghost_filter.lookback",
                      "expected >= 1 frame, got " + std::to_string(cfg.lookback));
  if (!(cfg.onset > 0.0))
    throw ConfigError("ghost_filter.onset", "expected > 0 (g units), got " + num(cfg.onset));
  if (!(cfg.release >= 0.0))
    throw ConfigError("ghost_filter.release", "expected >= 0 (g units), got " + num(cfg.release));
  if (!(cfg.pair_tol >= 0.0))
    throw ConfigError("ghost_filter.pair_tol", "expected >= 0 (g units), got " + num(cfg.pair_tol));
  history_.assign(size_t(cfg.lookback), Eigen::VectorXd::Zero(rows + cols));
  g_ = Eigen::MatrixXd::Zero(rows, cols);
  prev_lines_ = Eigen::VectorXd::Zero(rows + cols);
}

void GhostFilter::add_site(int r, int c) {
  if (std::find(sites_.begin(), sites_.end(), std::make_pair(r, c)) == sites_.end())
    sites_.emplace_back(r, c);
}

void GhostFilter::add_thesis(const Eigen::VectorXd& rise) {
  Eigen::Index r, c;
  double rmax = rise.head(rows_).maxCoeff(&r);
  double cmax = rise.tail(cols_).maxCoeff(&c);
  if (rmax > cfg_.onset && cmax > cfg_.onset) add_site(int(r), int(c));
}

std::vector<std::vector<std::pair<int, int>>> GhostFilter::fit_pairings(
    const Eigen::VectorXd& rise) const {
  std::vector<std::vector<std::pair<int, int>>> out;
  std::vector<int> rs, cs;  // rising rows, rising columns
  for (int i = 0; i < rows_; ++i)
    if (rise[i] > cfg_.onset) rs.push_back(i);
  for (int j = 0; j < cols_; ++j)
    if (rise[rows_ + j] > cfg_.onset) cs.push_back(j);
  if (rs.empty() || cs.empty()) return out;

  const int nr = int(rs.size()), nc = int(cs.size()), K = nr * nc;
  if (K > kMaxEnumerated) {
    // Too many crossings to enumerate: pair one to one in order of rise.
    auto by_rise = [&rise](int off) {
      return [&rise, off](int a, int b) { return rise[off + a] > rise[off + b]; };
    };
    std::sort(rs.begin(), rs.end(), by_rise(0));
    std::sort(cs.begin(), cs.end(), by_rise(rows_));
    out.emplace_back();
    for (int k = 0; k < std::min(nr, nc); ++k) out[0].emplace_back(rs[size_t(k)], cs[size_t(k)]);
    return out;
  }

  // Local problem: lines are the rising rows then the rising columns,
  // candidates are their crossings, bit k of a mask = crossing (k / nc, k % nc).
  Eigen::VectorXd b(nr + nc);
  for (int i = 0; i < nr; ++i) b[i] = rise[rs[size_t(i)]];
  for (int j = 0; j < nc; ++j) b[nr + j] = rise[rows_ + cs[size_t(j)]];
  const unsigned full_rows = (1u << nr) - 1, full_cols = (1u << nc) - 1;

  // A crossing set with more than nr + nc - 1 members contains a cycle, so a
  // smaller one explains the same rises: sizes beyond that are never needed.
  for (int size = std::max(nr, nc); size <= std::min(K, nr + nc - 1); ++size) {
    for (unsigned mask = 0; mask < (1u << K); ++mask) {
      if (__builtin_popcount(mask) != size) continue;
      unsigned rows_hit = 0, cols_hit = 0;
      for (int k = 0; k < K; ++k)
        if (mask >> k & 1u) rows_hit |= 1u << (k / nc), cols_hit |= 1u << (k % nc);
      if (rows_hit != full_rows || cols_hit != full_cols) continue;
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nr + nc, size);
      int s = 0;
      for (int k = 0; k < K; ++k)
        if (mask >> k & 1u) A(k / nc, s) = 1.0, A(nr + k % nc, s) = 1.0, ++s;
      Eigen::VectorXd x = nnls(A, b);
      double err = (A * x - b).cwiseAbs().maxCoeff();
      if (err <= cfg_.pair_tol && (x.array() > 0.0).all()) {
        out.emplace_back();
        for (int k = 0; k < K; ++k)
          if (mask >> k & 1u) out.back().emplace_back(rs[size_t(k / nc)], cs[size_t(k % nc)]);
      }
    }
    if (!out.empty()) return out;
  }
  return out;  // no consistent pairing (e.g. a line's partner stayed below onset)
}

bool GhostFilter::all_active(const std::vector<std::pair<int, int>>& set) const {
  for (const auto& s : set)
    if (std::find(sites_.begin(), sites_.end(), s) == sites_.end()) return false;
  return true;
}

void GhostFilter::commit(const std::vector<std::vector<std::pair<int, int>>>& fits) {
  if (fits.size() > 1) ambiguous_ = true;
  for (const auto& set : fits)
    for (const auto& s : set) add_site(s.first, s.second);
}

void GhostFilter::add_paired(const Eigen::VectorXd& lines, const Eigen::VectorXd& before) {
  const int L = rows_ + cols_;
  const Eigen::VectorXd rise = lines - before;  // over `lookback` frames
  bool stopped = false;
  Eigen::VectorXd eval = rise;
  if (pending_) {
    // Lines that start rising while a decision waits join it.
    bool grew = false, rising = false;
    for (int k = 0; k < L; ++k) {
      if (!pend_line_[size_t(k)] && rise[k] > cfg_.onset)
        pend_line_[size_t(k)] = true, pend_base_[k] = before[k];
      if (!pend_line_[size_t(k)]) continue;
      grew |= lines[k] > prev_lines_[k];
      rising |= rise[k] > cfg_.onset;
    }
    // Rise since each pending line's onset; other lines do not take part.
    for (int k = 0; k < L; ++k) eval[k] = pend_line_[size_t(k)] ? lines[k] - pend_base_[k] : 0.0;
    stopped = !grew || !rising;
  }
  const auto fits = fit_pairings(eval);
  if (fits.size() > 1)
    for (const auto& set : fits)
      if (all_active(set)) return end_pending();  // the active sites already explain it
  if (fits.size() == 1) {
    commit(fits);
    return end_pending();
  }
  if (!pending_) {
    if (fits.empty()) return add_thesis(rise);
    // Ambiguous at onset: wait for the rises to tell the candidates apart.
    pending_ = true;
    pend_line_.assign(size_t(L), false);
    pend_base_ = before;
    for (int k = 0; k < L; ++k) pend_line_[size_t(k)] = rise[k] > cfg_.onset;
  }
  if (!fits.empty()) pend_fits_ = fits;
  if (stopped) {
    commit(pend_fits_);  // still ambiguous: keep them all so that no touch is lost
    end_pending();
  }
}

void GhostFilter::end_pending() {
  pending_ = false;
  pend_fits_.clear();
}

void GhostFilter::solve_values(const Eigen::VectorXd& lines) {
  const int L = rows_ + cols_;
  for (;;) {
    const Eigen::Index n = Eigen::Index(sites_.size());
    if (cfg_.simultaneous) {
      Eigen::MatrixXd A(L + n, n);
      A.topRows(L) = incidence(sites_, rows_, L);
      A.bottomRows(n) = std::sqrt(kRidge) * Eigen::MatrixXd::Identity(n, n);
      Eigen::VectorXd b = Eigen::VectorXd::Zero(L + n);
      b.head(L) = lines;
      values_ = nnls(A, b);
    } else {
      values_.resize(n);
      for (Eigen::Index s = 0; s < n; ++s) {
        double r = std::max(0.0, lines[sites_[size_t(s)].first]);
        double c = std::max(0.0, lines[rows_ + sites_[size_t(s)].second]);
        values_[s] = std::sqrt(r * c);
      }
    }
    // Release; in the joint solve a removed site's share goes back to the
    // others, so solve again until the set is stable.
    std::vector<std::pair<int, int>> kept;
    for (Eigen::Index s = 0; s < n; ++s)
      if (values_[s] >= cfg_.release) kept.push_back(sites_[size_t(s)]);
    if (Eigen::Index(kept.size()) == n) break;
    sites_ = std::move(kept);
  }
}

const Eigen::MatrixXd& GhostFilter::update(const Eigen::VectorXd& row_g,
                                           const Eigen::VectorXd& col_g) {
  if (row_g.size() != rows_)
    throw ConfigError("ghost_filter.row_g", "expected " + std::to_string(rows_) +
                                                " row amplitudes, got " +
                                                std::to_string(row_g.size()));
  if (col_g.size() != cols_)
    throw ConfigError("ghost_filter.col_g", "expected " + std::to_string(cols_) +
                                                " column amplitudes, got " +
                                                std::to_string(col_g.size()));
  Eigen::VectorXd lines(rows_ + cols_);
  lines << row_g, col_g;
  const Eigen::VectorXd before = history_[size_t(head_)];  // `lookback` frames ago
  history_[size_t(head_)] = lines;
  head_ = (head_ + 1) % cfg_.lookback;

  if (cfg_.simultaneous)
    add_paired(lines, before);
  else
    add_thesis(lines - before);
  prev_lines_ = lines;
  solve_values(lines);

  g_.setZero();
  for (size_t s = 0; s < sites_.size(); ++s)
    g_(sites_[s].first, sites_[s].second) = values_[Eigen::Index(s)];
  return g_;
}

}  // namespace eskin::golden
