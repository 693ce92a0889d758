// frame_bound: the static bound (see the header).
#include "ucode/frame_bound.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include "ucode/frame_engine.h"

namespace eskin::hls::fe_bound {
namespace {

using namespace eskin::hls::fe;

constexpr uint64_t kSat = std::numeric_limits<uint64_t>::max() / 4;
uint64_t sat_add(uint64_t a, uint64_t b) { return std::min(kSat, a + b); }
uint64_t sat_mul(uint64_t a, uint64_t b) {
  return a == 0 || b == 0 ? 0 : (a > kSat / b ? kSat : std::min(kSat, a * b));
}

enum class Edge { kFall, kTaken };
struct Succ {
  uint32_t to;
  Edge kind;
};

// One strongly connected part's loop: its nodes, its counted branches and
// their taken edges, the most times those are taken per entry.
struct Loop {
  std::vector<uint32_t> body;  // addresses, sorted
  std::vector<uint32_t> branches;
  uint64_t taken = 0;
  int reg = 0;          // a djnz loop's register (its count: djnz_taken), 0: .bound
  int64_t per = -1;     // .bound's LOOP: `taken` counts per entry of the loop jumping back there
  uint64_t extra = 0;   // the loops counted per entry of this one: their passes beyond one per entry
  bool collapsed = false;
};

class Analyzer {
 public:
  Analyzer(const fe_asm::Program& prog, const Options& opt) : prog_(prog), opt_(opt) {
    n_ = uint32_t(prog.words.size());
    line_of_.assign(n_, nullptr);
    for (const auto& l : prog.listing)
      if (l.has_word && l.addr < n_ && !line_of_[l.addr]) line_of_[l.addr] = &l;
    for (const auto& [addr, b] : prog.bounds) {
      (void)b;
      if (addr >= n_) continue;
      const uint32_t w = prog.words[addr];
      const bool branch = cls_of(w) == kCtl && (fn_of(w) == kJ || fn_of(w) == kDjnz);
      const bool loaded_shift = is_shift(w) && cls_of(w) != kImm;
      if (!branch && !loaded_shift)
        fail(addr, ".bound: expected a branch (j, djnz) or a shift by a memory / P count after it");
    }
    // Each instruction's bubble: whether any instruction that can come
    // before it leaves a hazard it cannot overlap (none before it: the
    // start of a path, counted as a bubble).
    std::vector<bool> has_pred(n_, false);
    bubble_.assign(n_, false);
    auto pred = [&](uint32_t v, const Hazard& h) {
      if (v >= n_) return;
      has_pred[v] = true;
      if (!overlaps(h, prog_.words[v])) bubble_[v] = true;
    };
    for (uint32_t a = 0; a < n_; ++a) {
      const uint32_t w = prog_.words[a];
      if (cls_of(w) == kCtl && fn_of(w) == kCall) {
        pred(addr_of(w), hazard_after(w, 0));
        pred(a + 1, hazard_after(ctl(kRet, 0, 0, 0), 0));  // after the callee's ret
        continue;
      }
      if (cls_of(w) == kCtl && fn_of(w) == kRet) continue;
      const Hazard h = hazard_after(w, worst_count(a));
      for (const Succ& s : succ(a)) pred(s.to, h);
    }
    for (uint32_t a = 0; a < n_; ++a)
      if (!has_pred[a]) bubble_[a] = true;
  }

  std::map<uint32_t, uint64_t> run(uint32_t from, const std::set<uint32_t>& stops, bool routine) {
    check_addr(from, from);
    // The region: every address reachable from `from`, stopping at the
    // stops (not entered) and, in a routine, at its `ret` (a sink).
    std::vector<uint32_t> nodes;
    std::vector<int> index(n_, -1);
    std::vector<uint32_t> work = {from};
    index[from] = 0;
    nodes.push_back(from);
    while (!work.empty()) {
      const uint32_t a = work.back();
      work.pop_back();
      const uint32_t w = prog_.words[a];
      if (cls_of(w) == kCtl && fn_of(w) == kRet) {
        if (!routine) fail(a, "ret outside a call (the path from the start returns)");
        continue;
      }
      for (const Succ& s : succ(a)) {
        check_addr(a, s.to);
        if (stops.count(s.to) || index[s.to] >= 0) continue;
        index[s.to] = int(nodes.size());
        nodes.push_back(s.to);
        work.push_back(s.to);
      }
    }
    std::sort(nodes.begin(), nodes.end());
    for (size_t i = 0; i < nodes.size(); ++i) index[nodes[i]] = int(i);
    const size_t nn = nodes.size();

    // Edges between region nodes; counted: the taken edges of djnz x1..x3
    // and of branches with a .bound.
    struct E {
      int u, v;
      bool counted;
      int reg;          // djnz register without .bound (0: annotated or not counted)
      bool normal = false;  // a counted edge on no cycle: an ordinary edge
    };
    std::vector<E> edges;
    std::vector<std::pair<int, uint32_t>> to_stop;  // (node, stop address)
    for (size_t i = 0; i < nn; ++i) {
      const uint32_t a = nodes[i], w = prog_.words[a];
      if (cls_of(w) == kCtl && fn_of(w) == kRet) continue;
      const bool annotated = prog_.bounds.count(a) && cls_of(w) == kCtl;
      const bool djnz = cls_of(w) == kCtl && fn_of(w) == kDjnz && x_of(w) != 0;
      for (const Succ& s : succ(a)) {
        if (stops.count(s.to)) {
          to_stop.emplace_back(int(i), s.to);
          continue;
        }
        const bool counted = s.kind == Edge::kTaken && (annotated || djnz);
        edges.push_back({int(i), index[s.to], counted, counted && !annotated ? int(x_of(w)) : 0});
      }
    }

    // Strongly connected parts of the region's nodes over a set of edges.
    auto sccs = [&](const std::function<bool(const E&)>& use, const std::vector<int>* map) {
      std::vector<std::vector<int>> out(nn);
      for (const E& e : edges)
        if (use(e)) {
          if (map) out[size_t((*map)[size_t(e.u)])].push_back((*map)[size_t(e.v)]);
          else out[size_t(e.u)].push_back(e.v);
        }
      std::vector<int> comp(nn, -1), low(nn, 0), num(nn, -1), stack;
      std::vector<bool> on(nn, false);
      int counter = 0, ncomp = 0;
      // Iterative Tarjan.
      for (size_t s0 = 0; s0 < nn; ++s0) {
        if (num[s0] >= 0) continue;
        std::vector<std::pair<int, size_t>> call = {{int(s0), 0}};
        num[s0] = low[s0] = counter++;
        stack.push_back(int(s0));
        on[s0] = true;
        while (!call.empty()) {
          auto& [v, it] = call.back();
          if (it < out[size_t(v)].size()) {
            const int w = out[size_t(v)][it++];
            if (num[size_t(w)] < 0) {
              num[size_t(w)] = low[size_t(w)] = counter++;
              stack.push_back(w);
              on[size_t(w)] = true;
              call.push_back({w, 0});
            } else if (on[size_t(w)]) {
              low[size_t(v)] = std::min(low[size_t(v)], num[size_t(w)]);
            }
          } else {
            if (low[size_t(v)] == num[size_t(v)]) {
              for (;;) {
                const int w = stack.back();
                stack.pop_back();
                on[size_t(w)] = false;
                comp[size_t(w)] = ncomp;
                if (w == v) break;
              }
              ++ncomp;
            }
            const int done = v;
            call.pop_back();
            if (!call.empty())
              low[size_t(call.back().first)] = std::min(low[size_t(call.back().first)], low[size_t(done)]);
          }
        }
      }
      return comp;
    };
    // A cycle of `use`'s edges: the error, naming its closing branch (the
    // highest address in it with an edge back to a lower or equal one).
    auto no_cycle = [&](const std::function<bool(const E&)>& use, const char* what) {
      const std::vector<int> comp = sccs(use, nullptr);
      std::vector<int> size(nn, 0);
      for (size_t i = 0; i < nn; ++i) ++size[size_t(comp[i])];
      int worst = -1;
      for (const E& e : edges)
        if (use(e) && comp[size_t(e.u)] == comp[size_t(e.v)] &&
            (size[size_t(comp[size_t(e.u)])] > 1 || e.u == e.v) && e.v <= e.u)
          worst = std::max(worst, e.u);
      if (worst >= 0) fail(nodes[size_t(worst)], what);
    };
    no_cycle([](const E& e) { return !e.counted; },
             "unbounded loop: this branch closes a loop that no djnz with a constant count "
             "and no .bound bounds");

    // The loops: per register, the djnz taken edges without .bound with the
    // uncounted edges; per annotated branch, its taken edge with them.
    std::vector<Loop> loops;
    std::vector<int> loop_of_edge(edges.size(), -1);
    auto loop_from = [&](const std::function<bool(const E&)>& mine, uint64_t taken_annotated,
                         int reg) {
      const std::vector<int> comp = sccs([&](const E& e) { return !e.counted || mine(e); }, nullptr);
      std::map<int, int> by_comp;  // component -> loop index
      for (size_t k = 0; k < edges.size(); ++k) {
        const E& e = edges[k];
        if (!e.counted || !mine(e)) continue;
        if (comp[size_t(e.u)] != comp[size_t(e.v)]) {
          edges[k].normal = true;  // on no cycle: an ordinary (forward) edge
          continue;
        }
        auto [it, fresh] = by_comp.emplace(comp[size_t(e.u)], int(loops.size()));
        if (fresh) {
          Loop l;
          for (size_t i = 0; i < nn; ++i)
            if (comp[i] == comp[size_t(e.u)]) l.body.push_back(uint32_t(i));
          l.taken = taken_annotated;
          loops.push_back(l);
        }
        Loop& l = loops[size_t(it->second)];
        if (std::find(l.branches.begin(), l.branches.end(), uint32_t(e.u)) == l.branches.end())
          l.branches.push_back(uint32_t(e.u));
        loop_of_edge[k] = it->second;
      }
      for (const auto& [c, li] : by_comp) {
        (void)c;
        loops[size_t(li)].reg = reg;
      }
    };
    for (int reg = 1; reg <= 3; ++reg)
      loop_from([&](const E& e) { return e.reg == reg; }, 0, reg);
    for (size_t k = 0; k < edges.size(); ++k)
      if (edges[k].counted && edges[k].reg == 0) {
        const int u = edges[k].u;
        const size_t before = loops.size();
        const auto& bd = prog_.bounds.at(nodes[size_t(u)]);
        loop_from([&](const E& e) { return e.counted && e.reg == 0 && e.u == u; },
                  uint64_t(bd.count), 0);
        for (size_t li = before; li < loops.size(); ++li) loops[li].per = bd.per;
      }

    // Innermost first: each loop becomes one node of cost (taken + 1) x its
    // longest pass.
    std::vector<int> rep(nn);
    std::vector<uint64_t> cost(nn);
    for (size_t i = 0; i < nn; ++i) rep[i] = int(i), cost[i] = node_cost(nodes[i]);
    std::vector<size_t> order(loops.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
      return loops[x].body.size() != loops[y].body.size()
                 ? loops[x].body.size() < loops[y].body.size()
                 : (loops[x].per >= 0) > (loops[y].per >= 0);
    });
    // The loop a .bound's LOOP names: around l, with a counted branch back to it.
    auto outer = [&](const Loop& l) -> Loop& {
      for (Loop& o : loops) {
        if (&o == &l || o.collapsed ||
            !std::binary_search(o.body.begin(), o.body.end(), l.branches.front()))
          continue;
        for (uint32_t b : o.branches)
          for (const Succ& s : succ(nodes[b]))
            if (s.kind == Edge::kTaken && int64_t(s.to) == l.per) return o;
      }
      fail(nodes[l.branches.front()], ".bound: no loop around this one jumps back to address " +
                                          std::to_string(l.per));
    };
    auto usable = [&](size_t k) {  // an edge of the flow as it stands
      const E& e = edges[k];
      return !e.counted || e.normal || (loop_of_edge[k] >= 0 && loops[size_t(loop_of_edge[k])].collapsed);
    };
    for (size_t li : order) {
      Loop& l = loops[li];
      // Its body as the flow stands: the strongly connected part of its
      // branches among the nodes and the loops collapsed so far (which
      // reach nodes that only their counted edges lead to).
      {
        const std::vector<int> comp = sccs([&](const E& e) {
          const size_t k = size_t(&e - edges.data());
          return usable(k) || loop_of_edge[k] == int(li);
        }, &rep);
        const int c = comp[size_t(rep[l.branches.front()])];
        l.body.clear();
        for (size_t i = 0; i < nn; ++i)
          if (comp[size_t(rep[i])] == c) l.body.push_back(uint32_t(i));
      }
      // Its exits: a counted branch whose fall-through stays in the loop
      // would let its count run on (past 0 for a djnz).
      for (uint32_t b : l.branches)
        for (const Succ& s : succ(nodes[b]))
          if (s.kind == Edge::kFall && !stops.count(s.to) &&
              std::binary_search(l.body.begin(), l.body.end(), uint32_t(index[s.to])))
            fail(nodes[b], "loop: the branch's fall-through stays in its loop, so its count does "
                           "not bound the loop");
      if (l.reg) l.taken = djnz_taken(l, nodes, index, l.reg, from);
      std::vector<bool> in(nn, false);
      for (uint32_t i : l.body) in[i] = true;
      std::set<int> starts, ends;
      for (size_t k = 0; k < edges.size(); ++k) {
        const E& e = edges[k];
        if (!in[size_t(e.v)]) continue;
        if (!in[size_t(e.u)]) starts.insert(rep[size_t(e.v)]);
        else if (loop_of_edge[k] == int(li)) starts.insert(rep[size_t(e.v)]);
        else if (loop_of_edge[k] >= 0 && !loops[size_t(loop_of_edge[k])].collapsed)
          fail(nodes[size_t(e.u)], "loop: the loop this branch closes and the loop of the branch "
                                   "at address " + std::to_string(nodes[l.branches.front()]) +
                                   " are not nested");
      }
      if (in[size_t(index[from])]) starts.insert(rep[size_t(index[from])]);
      for (uint32_t b : l.branches) ends.insert(rep[b]);
      const uint64_t pass = longest_in(nn, rep, cost, edges.size(), [&](size_t k) {
        const E& e = edges[k];
        return in[size_t(e.u)] && in[size_t(e.v)] && usable(k) && loop_of_edge[k] != int(li);
      }, [&](size_t k) { return std::pair<int, int>{edges[k].u, edges[k].v}; }, starts, ends,
                                   nodes[l.branches.front()]);
      std::set<int> reps;
      for (uint32_t i : l.body) reps.insert(rep[i]);
      const int r = *reps.begin();
      for (size_t i = 0; i < nn; ++i)
        if (reps.count(rep[i])) rep[i] = r;
      if (l.per >= 0) {  // one pass per entry here, the rest once per entry of the outer loop
        Loop& o = outer(l);
        o.extra = sat_add(o.extra, sat_mul(l.taken, pass));
        cost[size_t(r)] = sat_add(pass, l.extra);
      } else {
        cost[size_t(r)] = sat_add(sat_mul(l.taken + 1, pass), l.extra);
      }
      l.collapsed = true;
      if (std::getenv("ESKIN_BOUND_DEBUG"))
        std::fprintf(stderr, "loop %u..%u (%zu nodes) branches at %u taken %llu per %lld: pass %llu, "
                     "cost %llu\n", nodes[l.body.front()], nodes[l.body.back()], l.body.size(),
                     nodes[l.branches.front()], (unsigned long long)l.taken, (long long)l.per,
                     (unsigned long long)pass, (unsigned long long)cost[size_t(r)]);
    }
    no_cycle([&](const E& e) {
      const size_t k = size_t(&e - edges.data());
      return usable(k) && rep[size_t(e.u)] != rep[size_t(e.v)];
    }, "unbounded loop: this branch closes a loop that its counted branches do not bound");

    // The whole region: the longest path from `from` to each stop (or, in
    // a routine, through a ret).
    std::set<int> start = {rep[size_t(index[from])]}, ends;
    if (routine) {
      for (size_t i = 0; i < nn; ++i) {
        const uint32_t w = prog_.words[nodes[i]];
        if (cls_of(w) == kCtl && fn_of(w) == kRet) ends.insert(rep[i]);
      }
    } else {
      for (const auto& [i, s] : to_stop) { (void)s; ends.insert(rep[size_t(i)]); }
    }
    std::vector<uint64_t> dist;
    longest_in(nn, rep, cost, edges.size(), [&](size_t k) {
      return usable(k) && rep[size_t(edges[k].u)] != rep[size_t(edges[k].v)];
    }, [&](size_t k) { return std::pair<int, int>{edges[k].u, edges[k].v}; }, start, ends, from,
               &dist);
    std::map<uint32_t, uint64_t> out;
    if (routine) {
      uint64_t m = 0;
      for (int e : ends) m = std::max(m, dist[size_t(e)]);
      out[from] = m;
    } else {
      for (const auto& [i, s] : to_stop) {
        const uint64_t d = dist[size_t(rep[size_t(i)])];
        out[s] = std::max(out.count(s) ? out[s] : 0, d);
      }
    }
    return out;
  }

 private:
  [[noreturn]] void fail(uint32_t addr, const std::string& msg) const {
    const fe_asm::ListingLine* l = addr < n_ ? line_of_[addr] : nullptr;
    std::string where = opt_.file + ":" + (l ? std::to_string(l->line) : std::string("?"));
    std::string text = l ? l->text : std::string();
    const size_t b = text.find_first_not_of(" \t");
    text = b == std::string::npos ? "" : text.substr(b);
    throw BoundError(where + ": " + msg + " (address " + std::to_string(addr) +
                     (text.empty() ? "" : ": " + text) + ")");
  }
  void check_addr(uint32_t at, uint32_t a) const {
    if (a >= n_) fail(at, "the path runs past the end of the program (address " +
                          std::to_string(a) + ")");
  }

  std::vector<Succ> succ(uint32_t a) const {
    const uint32_t w = prog_.words[a];
    if (cls_of(w) != kCtl) return {{a + 1, Edge::kFall}};
    const uint32_t t = addr_of(w);
    switch (fn_of(w)) {
      case kJ: {
        const uint32_t c = field_of(w);
        if (c == kAlways) return {{t, Edge::kTaken}};
        if (c == kNever) return {{a + 1, Edge::kFall}};
        return {{a + 1, Edge::kFall}, {t, Edge::kTaken}};
      }
      case kDjnz:
        if (x_of(w) == 0) return {{t, Edge::kTaken}};
        return {{a + 1, Edge::kFall}, {t, Edge::kTaken}};
      case kRet: return {};
      default: return {{a + 1, Edge::kFall}};  // call: after its callee
    }
  }

  // A shift's count, its worst for the next instruction (a loaded count
  // may be 0: no overlap), for hazard_after.
  uint32_t worst_count(uint32_t a) const {
    const uint32_t w = prog_.words[a];
    if (!is_shift(w)) return 0;
    return cls_of(w) == kImm ? uint32_t(imm_of(w)) & 63u : 0u;
  }

  uint64_t node_cost(uint32_t a) {
    const uint32_t w = prog_.words[a];
    const uint64_t bubble = bubble_[a] ? 1 : 0;
    if (cls_of(w) == kCtl && fn_of(w) == kWait) {
      const auto it = opt_.wait_clocks.find(uint16_t(addr_of(w)));
      if (it == opt_.wait_clocks.end())
        fail(a, "wait: no bound is known for its events (mask " + std::to_string(addr_of(w)) + ")");
      const uint64_t most = it->second;
      const auto st = opt_.wait_starts.find(uint16_t(addr_of(w)));
      if (st == opt_.wait_starts.end()) return bubble + most;
      const uint64_t e = since_start(a, st->second);
      return std::max<uint64_t>(bubble + 1, most > e ? most - e : 0);
    }
    if (cls_of(w) == kCtl && fn_of(w) == kCall)
      return bubble + b_clocks(w, 0, opt_.fast_shift) + routine(addr_of(w), a);
    uint32_t n = worst_count(a);
    if (is_shift(w) && cls_of(w) != kImm) {
      const auto it = prog_.bounds.find(a);
      n = it == prog_.bounds.end() ? 63u : uint32_t(std::min<int64_t>(63, it->second.count));
    }
    return bubble + b_clocks(w, n, opt_.fast_shift);
  }

  // The fewest clocks an instruction can take (no bubble, a loaded shift
  // count of 0, a wait's one clock, a call's own clock without its callee).
  uint64_t min_clocks(uint32_t a) const {
    const uint32_t w = prog_.words[a];
    if (cls_of(w) == kCtl && fn_of(w) == kWait) return 1;
    return b_clocks(w, worst_count(a), opt_.fast_shift);
  }
  // Whether the instruction at a may start what `starts` names: an `out` to
  // one of those IO addresses, or to any indexed by x.
  bool starts_at(uint32_t a, const std::set<uint16_t>& starts) const {
    const uint32_t w = prog_.words[a];
    return cls_of(w) == kMem && fn_of(w) == kOut && space_of(w) == kIo &&
           (x_of(w) != 0 || starts.count(uint16_t(addr_of(w))));
  }
  // Whether the routine at `entry` (or one it calls) may start what
  // `starts` names.
  bool routine_starts(uint32_t entry, const std::set<uint16_t>& starts) {
    const auto key = std::make_pair(entry, starts);
    if (const auto it = starts_.find(key); it != starts_.end()) return it->second;
    starts_[key] = false;  // (a recursive call adds nothing new)
    bool s = false;
    for (uint32_t a : routine_body(entry)) {
      const uint32_t w = prog_.words[a];
      s = s || starts_at(a, starts) ||
          (cls_of(w) == kCtl && fn_of(w) == kCall && addr_of(w) < n_ &&
           routine_starts(addr_of(w), starts));
    }
    return starts_[key] = s;
  }
  // The fewest clocks any path spends between the latest start (`starts`)
  // and the wait at `wait`, neither counted: shortest paths backwards over
  // the instructions' fewest clocks (a callee passed on the way back: none,
  // or the end of the walk when it may start; a routine's entry: back to
  // each of its calls).
  uint64_t since_start(uint32_t wait, const std::set<uint16_t>& starts) {
    const auto key = std::make_pair(wait, starts);
    if (const auto it = since_.find(key); it != since_.end()) return it->second;
    constexpr uint64_t kInf = std::numeric_limits<uint64_t>::max();
    std::vector<uint64_t> d(n_, kInf);  // clocks between the end of a and the wait
    using Item = std::pair<uint64_t, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
    uint64_t best = kInf;
    auto reach = [&](uint32_t p, uint64_t dist) {
      if (dist >= d[p] || dist >= best) return;
      d[p] = dist;
      if (starts_at(p, starts)) best = std::min(best, dist);
      else q.push({dist, p});
    };
    auto back = [&](uint32_t v, uint64_t dist) {  // the instructions before v
      if (preds(v).empty()) best = std::min(best, dist);  // reset: as if a start
      for (uint32_t p : preds(v)) {
        const uint32_t w = prog_.words[p];
        const bool call = cls_of(w) == kCtl && fn_of(w) == kCall;
        if (call && p + 1 == v && routine_starts(addr_of(w), starts)) {
          best = std::min(best, dist);  // its callee may start last
          if (addr_of(w) != v) continue;
        }
        reach(p, dist);
      }
    };
    back(wait, 0);
    while (!q.empty()) {
      const auto [dist, v] = q.top();
      q.pop();
      if (dist != d[v]) continue;
      back(v, sat_add(dist, min_clocks(v)));
    }
    return since_[key] = best == kInf ? 0 : best;
  }

  uint64_t routine(uint32_t entry, uint32_t caller) {
    check_addr(caller, entry);
    if (const auto it = routines_.find(entry); it != routines_.end()) {
      if (!it->second) fail(caller, "call: the routine calls itself (no bound)");
      return *it->second;
    }
    routines_[entry] = std::nullopt;
    const uint64_t c = run(entry, {}, true).at(entry);
    routines_[entry] = c;
    if (std::getenv("ESKIN_BOUND_DEBUG"))
      std::fprintf(stderr, "routine at %u (line %d): %llu clocks\n", entry,
                   line_of_[entry] ? line_of_[entry]->line : 0, (unsigned long long)c);
    return c;
  }

  // Which x registers the instruction at a (with its callees) may write.
  unsigned writes(uint32_t a) {
    const uint32_t w = prog_.words[a];
    if (cls_of(w) != kCtl) return 0;
    switch (fn_of(w)) {
      case kLdx: case kAddx: case kTax: case kDjnz: return 1u << x_of(w);
      case kCall: return routine_writes(addr_of(w));
      default: return 0;
    }
  }
  unsigned routine_writes(uint32_t entry) {
    if (const auto it = writes_.find(entry); it != writes_.end()) return it->second;
    writes_[entry] = 0;  // (a recursive call adds nothing new)
    unsigned m = 0;
    for (uint32_t a : routine_body(entry)) m |= writes(a);
    return writes_[entry] = m;
  }
  // The addresses the routine at `entry` reaches without entering its
  // callees (a call goes on after its callee).
  std::vector<uint32_t> routine_body(uint32_t entry) const {
    std::vector<bool> seen(n_, false);
    std::vector<uint32_t> work = {entry}, body;
    seen[entry] = true;
    while (!work.empty()) {
      const uint32_t a = work.back();
      work.pop_back();
      body.push_back(a);
      for (const Succ& s : succ(a))
        if (s.to < n_ && !seen[s.to]) seen[s.to] = true, work.push_back(s.to);
    }
    return body;
  }

  // The value of x`reg` after the instruction at `a` when every path to
  // it sets it with ldx (the largest of those), else none: a walk back over
  // the predecessors to the nearest writes of x`reg`.
  std::optional<int64_t> constant_after(uint32_t a, int reg) {
    std::vector<bool> seen(n_, false);
    std::vector<uint32_t> work = {a};
    seen[a] = true;
    int64_t v = -1;
    size_t visited = 0;
    while (!work.empty()) {
      const uint32_t u = work.back();
      work.pop_back();
      if (++visited > 4096) return std::nullopt;
      const uint32_t w = prog_.words[u];
      if (writes(u) & (1u << reg)) {
        if (!(cls_of(w) == kCtl && fn_of(w) == kLdx)) return std::nullopt;
        v = std::max<int64_t>(v, addr_of(w));
        continue;
      }
      if (preds(u).empty()) return std::nullopt;  // the program's start: x is unknown
      for (uint32_t p : preds(u))
        if (!seen[p]) seen[p] = true, work.push_back(p);
    }
    if (v < 0) return std::nullopt;
    return v;
  }
  const std::vector<uint32_t>& preds(uint32_t a) {
    if (preds_.empty()) {
      preds_.resize(n_);
      for (uint32_t u = 0; u < n_; ++u) {
        const uint32_t w = prog_.words[u];
        if (cls_of(w) == kCtl && fn_of(w) == kCall) {
          if (addr_of(w) < n_) preds_[addr_of(w)].push_back(u);
          if (u + 1 < n_) preds_[u + 1].push_back(u);  // (u writes what its callee writes)
          continue;
        }
        for (const Succ& s : succ(u))
          if (s.to < n_) preds_[s.to].push_back(u);
      }
    }
    return preds_[a];
  }

  // A djnz loop's taken bound: N - 1 for the constant N its register holds
  // at every entry (nothing in the loop but its djnz changes it).
  uint64_t djnz_taken(const Loop& l, const std::vector<uint32_t>& nodes,
                      const std::vector<int>& index, int reg, uint32_t from) {
    std::vector<bool> in(nodes.size(), false), branch(nodes.size(), false);
    for (uint32_t i : l.body) in[i] = true;
    for (uint32_t b : l.branches) branch[b] = true;
    const uint32_t first = nodes[l.branches.front()];
    for (uint32_t i : l.body)
      if (!branch[i] && (writes(nodes[i]) & (1u << reg)))
        fail(first, "djnz: x" + std::to_string(reg) + " changes in its loop (address " +
                        std::to_string(nodes[i]) + "), so its count is not a constant: give the "
                        "loop a .bound");
    if (in[size_t(index[from])])
      fail(first, "djnz: the loop is entered where the analysis starts, with x" +
                      std::to_string(reg) + " unknown: give the loop a .bound");
    int64_t n = -1;
    for (uint32_t i : l.body)
      for (uint32_t p : preds(nodes[i])) {
        if (index[p] >= 0 && in[size_t(index[p])]) continue;
        const auto v = constant_after(p, reg);
        if (!v)
          fail(first, "djnz: x" + std::to_string(reg) + " is not loaded with a constant (ldx) on "
                      "every path into its loop (from address " + std::to_string(p) +
                      "): give the loop a .bound");
        n = std::max(n, *v);
      }
    if (n < 0) fail(first, "djnz: no entry into its loop");
    return n == 0 ? 65535u : uint64_t(n - 1);
  }

  // The longest path (node costs) over the edges `use` picks, mapped to
  // their representatives, from any of `starts` to any of `ends` (cost
  // included). `dist_out` gets every node's distance.
  uint64_t longest_in(size_t nn, const std::vector<int>& rep, const std::vector<uint64_t>& cost,
                      size_t nedges, const std::function<bool(size_t)>& use,
                      const std::function<std::pair<int, int>(size_t)>& edge,
                      const std::set<int>& starts, const std::set<int>& ends, uint32_t where,
                      std::vector<uint64_t>* dist_out = nullptr) {
    std::vector<std::vector<int>> out(nn);
    std::vector<int> indeg(nn, 0);
    for (size_t k = 0; k < nedges; ++k) {
      if (!use(k)) continue;
      const auto [u, v] = edge(k);
      const int ru = rep[size_t(u)], rv = rep[size_t(v)];
      if (ru == rv) continue;
      out[size_t(ru)].push_back(rv);
      ++indeg[size_t(rv)];
    }
    std::vector<int> ready, topo;
    for (size_t i = 0; i < nn; ++i)
      if (rep[i] == int(i) && indeg[i] == 0) ready.push_back(int(i));
    while (!ready.empty()) {
      const int u = ready.back();
      ready.pop_back();
      topo.push_back(u);
      for (int v : out[size_t(u)])
        if (--indeg[size_t(v)] == 0) ready.push_back(v);
    }
    size_t live = 0;
    for (size_t i = 0; i < nn; ++i) live += rep[i] == int(i);
    if (topo.size() != live) fail(where, "loop: a cycle its counted branches do not bound");
    constexpr uint64_t kNone = ~uint64_t(0);
    std::vector<uint64_t> dist(nn, kNone);
    for (int u : topo) {
      if (starts.count(u)) dist[size_t(u)] = std::max(dist[size_t(u)] == kNone ? 0 : dist[size_t(u)],
                                                      cost[size_t(u)]);
      if (dist[size_t(u)] == kNone) continue;
      for (int v : out[size_t(u)]) {
        const uint64_t d = sat_add(dist[size_t(u)], cost[size_t(v)]);
        if (dist[size_t(v)] == kNone || d > dist[size_t(v)]) dist[size_t(v)] = d;
      }
    }
    uint64_t m = 0;
    for (int e : ends)
      if (dist[size_t(e)] != kNone) m = std::max(m, dist[size_t(e)]);
    if (dist_out) {
      for (auto& d : dist)
        if (d == kNone) d = 0;
      *dist_out = dist;
    }
    return m;
  }

  const fe_asm::Program& prog_;
  Options opt_;
  uint32_t n_ = 0;
  std::vector<const fe_asm::ListingLine*> line_of_;
  std::vector<bool> bubble_;
  std::map<uint32_t, std::optional<uint64_t>> routines_;
  std::map<uint32_t, unsigned> writes_;
  std::vector<std::vector<uint32_t>> preds_;
  std::map<std::pair<uint32_t, std::set<uint16_t>>, uint64_t> since_;
  std::map<std::pair<uint32_t, std::set<uint16_t>>, bool> starts_;
};

}  // namespace

std::map<uint32_t, uint64_t> longest_clocks(const fe_asm::Program& prog, uint32_t from,
                                            const std::set<uint32_t>& stops, const Options& opt) {
  Analyzer a(prog, opt);
  return a.run(from, stops, false);
}

uint64_t routine_clocks(const fe_asm::Program& prog, uint32_t entry, const Options& opt) {
  Analyzer a(prog, opt);
  return a.run(entry, {}, true).at(entry);
}

}  // namespace eskin::hls::fe_bound
