// Throughput of the golden amplitude estimators (host/golden/sdft_bank.h)
// against an FFTW full-overlap STFT (window N, hop 1, r2c, every sample) on
// the same ADC stream of a scene (world model, mid code subtracted).
// Workload per sample, both sides: push the sample, then read the magnitude
// of every carrier (golden: at the carrier frequency; FFTW: the nearest
// bin of the full N-point spectrum it computes anyway).
//
//   golden_bench [SCENE.yaml ...] [--min-seconds S]
// Default scenes: scenes/neuroskin2.yaml and scenes/skin32x32.yaml.
#include <fftw3.h>

#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

struct Result {
  double samples_per_s;
  double checksum;  // sum of all magnitudes of the last pass (keeps work alive)
};

// Thread CPU time: on a shared machine it excludes the time this thread is
// descheduled, so rates are far less noisy than with wall-clock time.
double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Repeats `pass` (one run over the stream, returning its checksum) until at
// least min_s CPU seconds have elapsed; returns the best single-pass rate.
Result timed(size_t samples, double min_s, const std::function<double()>& pass) {
  double best = 0.0, checksum = 0.0, total = 0.0;
  do {
    const double t0 = cpu_seconds();
    checksum = pass();
    const double dt = cpu_seconds() - t0;
    total += dt;
    best = std::max(best, double(samples) / dt);
  } while (total < min_s);
  return {best, checksum};
}

void bench_scene(const std::string& path, double min_s) {
  eskin::sim::Scene scene = eskin::sim::load_scene(path);
  eskin::sim::WorldModel world(scene);
  const std::vector<int> codes = world.all_codes();
  std::vector<double> x(codes.size());
  const double mid = scene.skin.adc.mid_code();
  for (size_t i = 0; i < codes.size(); ++i) x[i] = codes[i] - mid;
  const std::vector<double> freqs = scene.skin.carrier_freqs_hz();
  const double fs = scene.skin.adc.rate_hz;
  const eskin::DecoderConfig& dec = scene.decoder;
  const int n = dec.window, k = int(freqs.size());

  std::printf("\nscene %s: %d carriers, N = %d, fs = %.0f Hz, %zu samples, %s window\n",
              scene.name.c_str(), k, n, fs, x.size(), dec.hann ? "Hann" : "rectangular");

  // FFTW baseline: copy the window out of a doubled ring, r2c, magnitudes of
  // the bins nearest to the carriers.
  std::vector<int> nearest;
  for (double f : freqs) nearest.push_back(int(std::lround(f / fs * n)));
  double* in = fftw_alloc_real(size_t(n));
  fftw_complex* out = fftw_alloc_complex(size_t(n / 2 + 1));
  fftw_plan plan = fftw_plan_dft_r2c_1d(n, in, out, FFTW_MEASURE);
  std::vector<double> ring(2 * size_t(n), 0.0);
  Result fftw = timed(x.size(), min_s, [&] {
    std::fill(ring.begin(), ring.end(), 0.0);
    double sum = 0.0;
    size_t pos = 0;
    for (double v : x) {
      pos = pos + 1 == size_t(n) ? 0 : pos + 1;
      ring[pos] = ring[pos + size_t(n)] = v;
      std::memcpy(in, &ring[pos + 1], sizeof(double) * size_t(n));
      fftw_execute(plan);
      for (int b : nearest) sum += std::hypot(out[b][0], out[b][1]) * 2.0 / n;
    }
    return sum;
  });
  fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);

  std::printf("%-12s %14s %12s %14s %16s\n", "estimator", "samples/s", "ns/sample",
              "golden/FFTW", "sum |amplitude|");
  auto row = [&](const char* name, const Result& r) {
    std::printf("%-12s %14.4g %12.1f %14.3f %16.6g\n", name, r.samples_per_s,
                1e9 / r.samples_per_s, r.samples_per_s / fftw.samples_per_s, r.checksum);
  };
  row("fftw-stft", fftw);
  for (eskin::DftVariant v : {eskin::DftVariant::Direct, eskin::DftVariant::Recursive,
                              eskin::DftVariant::Damped, eskin::DftVariant::Exact,
                              eskin::DftVariant::LsDemix}) {
    Result r = timed(x.size(), min_s, [&] {
      auto bank = eskin::golden::make_sdft_bank(v, freqs, fs, dec);
      double sum = 0.0;
      for (double s : x) {
        bank->push(s);
        for (int c = 0; c < k; ++c) sum += bank->magnitude(c);
      }
      return sum;
    });
    row(eskin::to_string(v), r);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes;
  double min_s = 1.0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--min-seconds") == 0 && i + 1 < argc)
      min_s = std::atof(argv[++i]);
    else
      scenes.push_back(argv[i]);
  }
  if (scenes.empty())
    scenes = {std::string(ESKIN_SOURCE_DIR) + "/scenes/neuroskin2.yaml",
              std::string(ESKIN_SOURCE_DIR) + "/scenes/skin32x32.yaml"};
  std::printf("golden amplitude estimators vs FFTW %s STFT (hop 1); best pass of >= %.1f s CPU\n",
              fftw_version, min_s);
  try {
    for (const std::string& s : scenes) bench_scene(s, min_s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "golden_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
