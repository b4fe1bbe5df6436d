// The filter report of docs/filters.md, printed as Markdown:
//  1. each filter's integral by quadrature, its sampling weights, and its frequency and step
//     response (blur and ringing);
//  2. the antialiasing measurement: an emissive checkerboard receding to the horizon, rendered by
//     filmback through each filter in both reconstructions, against a closed-form reference.
//
// Definitions (docs/filters.md, "Aliasing"). R is the board's radiance averaged over the cells of
// a grid `scale` times finer than the pixels (from the closed form, `sub` x `sub` stratified
// points per cell). For a filter h:
//   J      = (h * R) at the pixel centres: what a converged render holds;
//   J_band = (lowpass(h * R)) at the pixel centres, lowpass keeping |f| < 1/2 cycle/px per axis:
//            the same filter with nothing above the pixel grid's Nyquist frequency left to fold;
//   I      = (lowpass(R)) at the pixel centres: an ideal (sinc) camera.
// Aliasing energy = mean over the frame of (J - J_band)^2: the error the pixel grid adds by
// folding frequencies above Nyquist back into the image. Blur = mean (J_band - I)^2: what the
// filter removes or distorts below Nyquist. Renders give J with noise; the noise is estimated
// from two seeds and subtracted.
//
// Usage: filmback_filter_report [--quick] [--images DIR]
//   --quick   a small frame and few samples: the CTest smoke run
//   --images  also write the reference and each filter's aliasing image J - J_band as EXR
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "band_limit.h"
#include "checkerboard.h"
#include "core/image/image_io.h"
#include "core/render/render_job.h"
#include "importers/gltf/gltf_importer.h"
#include "support/plugins.h"

namespace fb::filters {
namespace {

// The reference grid, scale (width + 2 margin_x) by scale (height + 2 margin_y) cells, must have
// sides that are powers of two (low_pass).
struct Settings {
  uint32_t width, height;       // the frame, px
  uint32_t margin_x, margin_y;  // reference beyond the frame, px
  uint32_t scale, sub;          // reference cells per px, points per cell per axis
  uint32_t spp_high, spp_low;   // converged renders (two seeds) and a low-spp one
  size_t weight_samples;        // for the weight statistics
  std::vector<std::string> filters;
};

Settings full_settings() {
  Settings s{192, 96, 32, 16, 8, 8, 1024, 16, 1000000, {}};
  s.filters = {"box",      "triangle", "triangle:radius=2",      "gaussian",
               "mitchell", "lanczos",  "lanczos:radius=4,tau=3", "blackman_harris"};
  return s;
}

Settings quick_settings() {
  Settings s{48, 32, 8, 16, 4, 2, 64, 4, 20000, {}};
  s.filters = {"box", "gaussian", "lanczos", "blackman_harris"};
  return s;
}

// ------------------------------------------------------------------ part 1: the filter alone

// The normalised 1-D profile h1 with h(x, y) = h1(x) h1(y), for the separable filters filmback
// ships; throws if the plugin's filter is not separable.
struct Profile {
  const FilterInstance& filter;
  float radius;
  double centre;
  explicit Profile(const FilterInstance& f) : filter(f), centre(f.evaluate(0.f, 0.f)) {
    float r[2];
    f.radius(r);
    radius = r[0];
    for (float x : {0.3f, 0.77f, 1.4f})
      for (float y : {0.2f, 0.9f})
        if (std::abs(f.evaluate(x * radius / 2, y * radius / 2) * centre -
                     f.evaluate(x * radius / 2, 0.f) * f.evaluate(0.f, y * radius / 2)) >
            1e-5 * centre * centre)
          throw std::runtime_error("the filter is not separable");
  }
  double operator()(double x) const { return filter.evaluate(float(x), 0.f) / std::sqrt(centre); }
  // Integral of h1 over [a, b] by the midpoint rule.
  double integral(double a, double b, int n = 64) const {
    double sum = 0;
    for (int i = 0; i < n; ++i)
      sum += (*this)(a + (i + 0.5) * (b - a) / n);
    return sum * (b - a) / n;
  }
};

struct FilterStats {
  double integral, quadrature;
  double weight_mean, weight_sd, abs_weight_relative_sd, weight_min, weight_max, negative;
  double response_quarter, response_nyquist;    // |H(f)| at f = 1/4 and 1/2 cycle/px
  double overshoot, undershoot, rise_10_90_px;  // of the step response
};

FilterStats filter_stats(const FilterInstance& filter, size_t samples) {
  FilterStats s{};
  s.integral = filter.integral();
  float r[2];
  filter.radius(r);
  const int n = 2000;  // the 2-D midpoint rule of filters_test.cpp
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      sum += filter.evaluate(-r[0] + (i + 0.5f) * 2 * r[0] / n, -r[1] + (j + 0.5f) * 2 * r[1] / n);
  s.quadrature = sum * (2.0 * r[0] / n) * (2.0 * r[1] / n);

  std::vector<float> u(2 * samples);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(0.f, 0.99999994f);
  for (float& x : u)
    x = uniform(rng);
  std::vector<fb_filter_sample> drawn(samples);
  filter.sample(u, drawn.data());
  double w1 = 0, w2 = 0, a1 = 0;
  s.weight_min = HUGE_VAL, s.weight_max = -HUGE_VAL;
  for (const fb_filter_sample& d : drawn) {
    w1 += d.weight, w2 += double(d.weight) * d.weight, a1 += std::abs(d.weight);
    s.negative += d.weight < 0;
    s.weight_min = std::min(s.weight_min, double(d.weight));
    s.weight_max = std::max(s.weight_max, double(d.weight));
  }
  const double m = double(samples);
  s.weight_mean = w1 / m;
  s.weight_sd = std::sqrt(std::max(0.0, w2 / m - s.weight_mean * s.weight_mean));
  s.abs_weight_relative_sd = std::sqrt(std::max(0.0, w2 / m - (a1 / m) * (a1 / m))) / (a1 / m);
  s.negative /= m;

  const Profile h1(filter);
  const int k = 20000;
  const double dx = 2.0 * h1.radius / k;
  double step = 0, lo = 0, hi = 0, x10 = NAN, x90 = NAN;
  for (int i = 0; i < k; ++i) {
    const double x = -h1.radius + (i + 0.5) * dx, v = h1(x);
    s.response_quarter += v * std::cos(2 * M_PI * 0.25 * x) * dx;
    s.response_nyquist += v * std::cos(2 * M_PI * 0.5 * x) * dx;
    step += v * dx;
    lo = std::min(lo, step), hi = std::max(hi, step);
    if (std::isnan(x10) && step >= 0.1) x10 = x;
    if (std::isnan(x90) && step >= 0.9) x90 = x;
  }
  s.response_quarter = std::abs(s.response_quarter);
  s.response_nyquist = std::abs(s.response_nyquist);
  s.overshoot = std::max(0.0, hi - 1), s.undershoot = std::max(0.0, -lo),
  s.rise_10_90_px = x90 - x10;
  return s;
}

// -------------------------------------------------------------- part 2: the antialiasing test

// The reference on the fine grid: cell a of a row is centred at raster x = a / scale - margin_x
// + 1/2, so pixel j's centre is cell scale (j + margin_x).
Grid reference(const Checkerboard& board, const Settings& s) {
  Grid r{size_t(s.scale) * (s.width + 2 * s.margin_x),
         size_t(s.scale) * (s.height + 2 * s.margin_y),
         {}};
  r.values.resize(r.width * r.height);
  tbb::parallel_for(size_t(0), r.height, [&](size_t b) {
    std::mt19937 rng{uint32_t(b)};
    std::uniform_real_distribution<double> jitter(0.0, 1.0);
    for (size_t a = 0; a < r.width; ++a) {
      const double x0 = (a - 0.5) / s.scale - s.margin_x + 0.5;
      const double y0 = (b - 0.5) / s.scale - s.margin_y + 0.5;
      double sum = 0;
      for (uint32_t j = 0; j < s.sub; ++j)
        for (uint32_t i = 0; i < s.sub; ++i)
          sum += board.radiance(x0 + (i + jitter(rng)) / (s.sub * s.scale),
                                y0 + (j + jitter(rng)) / (s.sub * s.scale));
      r.at(a, b) = sum / (s.sub * s.sub);
    }
  });
  return r;
}

// The fine-grid taps of h1: each the integral of h1 over one fine cell, in pixel units.
std::vector<double> taps(const Profile& h1, uint32_t scale) {
  const int half = int(std::ceil(h1.radius * scale + 0.5));
  std::vector<double> t;
  for (int d = -half; d <= half; ++d)
    t.push_back(h1.integral((d - 0.5) / scale, (d + 0.5) / scale));
  return t;
}

// Pixel values of a fine-grid image at the frame's pixel centres.
std::vector<double> at_pixel_centres(const Grid& g, const Settings& s) {
  std::vector<double> v;
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x)
      v.push_back(g.at(size_t(s.scale) * (x + s.margin_x), size_t(s.scale) * (y + s.margin_y)));
  return v;
}

double mean_square_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i)
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum / double(a.size());
}

std::vector<double> render(const Scene& scene, const Settings& s, const std::string& filter,
                           Reconstruction reconstruction, uint32_t spp, uint64_t seed,
                           double& seconds) {
  RenderOptions options;
  options.width = s.width, options.height = s.height;
  options.samples_per_pixel = spp, options.seed = seed;
  options.filter = filter, options.reconstruction = reconstruction;
  options.integrator = "path:max_depth=0";  // the emitters as seen: L itself
  options.show_progress = false;
  const RenderJob job(scene, options, test::loader());
  const RenderResult result = job.run();
  seconds += result.stats.seconds;
  if (result.stats.dropped_samples) throw std::runtime_error("non-finite samples in " + filter);
  std::vector<double> v;
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x)
      v.push_back(result.image.at(x, y, 1));
  return v;
}

void write_exr(const std::filesystem::path& file, const std::vector<double>& v, const Settings& s) {
  Image image{s.width, s.height, {"Y"}, std::vector<float>(v.begin(), v.end())};
  write_images(image, {file}, {});
}

struct Measured {
  double alias = 0, blur = 0;  // from the closed form
  struct Mode {
    double alias = 0, check = 0, noise_high = 0, low_error = 0, low_noise = 0, seconds = 0;
    size_t low_outliers = 0;
  } modes[2];
};

std::string machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

int run(int argc, char** argv) {
  bool quick = false;
  std::filesystem::path images;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--images") && i + 1 < argc) {
      images = argv[++i];
    } else {
      std::cerr << "usage: filmback_filter_report [--quick] [--images DIR]\n";
      return 2;
    }
  }
  const Settings s = quick ? quick_settings() : full_settings();
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::localtime(&now));
  std::printf("filter report, %s, %s, %d threads%s\n\n", date, machine().c_str(),
              tbb::info::default_concurrency(), quick ? " (--quick)" : "");

  std::printf(
      "## Filters\n\n%zu sampled weights each; H(f) is the 1-D frequency response, "
      "f in cycles/px.\n\n",
      s.weight_samples);
  std::printf(
      "| filter | integral | 2-D quadrature - 1 | weight mean | weight sd | sd(\\|w\\|) / "
      "mean\\|w\\| | weight range | negative | H(1/4) | H(1/2) | overshoot | undershoot "
      "| 10-90 %% rise (px) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& spec : s.filters) {
    const auto filter = test::make_filter(spec);
    const FilterStats f = filter_stats(*filter, s.weight_samples);
    std::printf(
        "| `%s` | %.6f | %.1e | %.5f | %.4f | %.1e | [%.4f, %.4f] | %.2f %% | %.3f | "
        "%.3f | %.2f %% | %.2f %% | %.2f |\n",
        spec.c_str(), f.integral, f.quadrature - 1, f.weight_mean, f.weight_sd,
        f.abs_weight_relative_sd, f.weight_min, f.weight_max, 100 * f.negative, f.response_quarter,
        f.response_nyquist, 100 * f.overshoot, 100 * f.undershoot, f.rise_10_90_px);
  }

  const Checkerboard board = make_checkerboard(s.width, s.height, std::max(s.margin_x, s.margin_y));
  const auto dir = std::filesystem::temp_directory_path() / "filmback-filter-report";
  std::filesystem::create_directories(dir);
  board.write_gltf(dir / "checkerboard.gltf");
  Diagnostics diagnostics;
  const Scene scene = import_gltf(dir / "checkerboard.gltf", diagnostics);

  const auto start = std::chrono::steady_clock::now();
  const Grid r = reference(board, s);
  const double cutoff = 0.5 / s.scale;  // Nyquist of the pixel grid, in cycles per fine cell
  const std::vector<double> ideal = at_pixel_centres(low_pass(r, cutoff), s);
  double mean = 0, variance = 0;
  for (double v : ideal)
    mean += v / double(ideal.size());
  for (double v : ideal)
    variance += (v - mean) * (v - mean) / double(ideal.size());
  const double reference_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!images.empty()) write_exr(images / "ideal.exr", ideal, s);

  std::printf(
      "\n## Aliasing\n\nCheckerboard to the horizon, %ux%u px, focal length %.0f px, "
      "horizon %.0f px from the top; reference grid %ux finer with %ux%u points per cell "
      "(%.1f s); converged renders %u spp x 2 seeds, low-spp renders %u spp. Energies "
      "are mean squares over the frame, in 1e-4 (radiance 0 or 1); the ideal image has "
      "variance %.1f e-4.\n\n",
      s.width, s.height, board.focal_px, 0.25 * s.height, s.scale, s.sub, s.sub, reference_s,
      s.spp_high, s.spp_low, variance * 1e4);
  std::vector<Measured> measured;
  for (const std::string& spec : s.filters) {
    const auto filter = test::make_filter(spec);
    const Profile h1(*filter);
    const Grid filtered = convolve_separable(r, taps(h1, s.scale));
    const std::vector<double> j = at_pixel_centres(filtered, s);
    const std::vector<double> band = at_pixel_centres(low_pass(filtered, cutoff), s);
    Measured& m = measured.emplace_back();
    m.alias = mean_square_difference(j, band);
    m.blur = mean_square_difference(band, ideal);
    for (int mode = 0; mode < 2; ++mode) {
      const auto reconstruction = mode ? Reconstruction::kSplat : Reconstruction::kImportance;
      Measured::Mode& out = m.modes[mode];
      const auto a = render(scene, s, spec, reconstruction, s.spp_high, 1, out.seconds);
      const auto b = render(scene, s, spec, reconstruction, s.spp_high, 2, out.seconds);
      std::vector<double> converged(a.size());
      for (size_t i = 0; i < a.size(); ++i)
        converged[i] = 0.5 * (a[i] + b[i]);
      out.noise_high = mean_square_difference(a, b) / 4;  // the variance of their mean
      out.alias = mean_square_difference(converged, band) - out.noise_high;
      out.check = std::sqrt(std::max(0.0, mean_square_difference(converged, j) - out.noise_high));
      double unused = 0;
      const auto low = render(scene, s, spec, reconstruction, s.spp_low, 3, unused);
      out.low_error = mean_square_difference(low, band);
      out.low_noise = mean_square_difference(low, converged);
      for (size_t i = 0; i < low.size(); ++i)
        out.low_outliers += std::abs(low[i] - band[i]) > 1;
      if (!images.empty() && mode == 0) {
        std::vector<double> alias_image(j.size());
        for (size_t i = 0; i < j.size(); ++i)
          alias_image[i] = j[i] - band[i];
        std::string name = spec;
        for (char& c : name)
          if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        write_exr(images / (name + "_aliasing.exr"), alias_image, s);
        write_exr(images / (name + "_render.exr"), converged, s);
      }
    }
    std::cerr << "measured " << spec << '\n';
  }

  std::printf(
      "Converged (%u spp x 2 seeds, noise subtracted):\n\n"
      "| filter | aliasing, importance | aliasing, splat | aliasing, closed form | blur "
      "| rms render - closed form, importance / splat |\n|---|---|---|---|---|---|\n",
      s.spp_high);
  for (size_t i = 0; i < s.filters.size(); ++i) {
    const Measured& m = measured[i];
    std::printf("| `%s` | %.2f | %.2f | %.2f | %.1f | %.4f / %.4f |\n", s.filters[i].c_str(),
                m.modes[0].alias * 1e4, m.modes[1].alias * 1e4, m.alias * 1e4, m.blur * 1e4,
                m.modes[0].check, m.modes[1].check);
  }
  std::printf(
      "\nAt %u spp (one seed): mean square error against J_band (aliasing and noise), "
      "the noise alone (against the converged render), pixels off by more than the "
      "full contrast, and the seconds of the two converged renders:\n\n"
      "| filter | error, importance / splat | noise, importance / splat | pixels off by "
      "> 1, importance / splat | seconds, importance / splat |\n|---|---|---|---|---|\n",
      s.spp_low);
  for (size_t i = 0; i < s.filters.size(); ++i) {
    const Measured::Mode(&m)[2] = measured[i].modes;
    std::printf("| `%s` | %.3g / %.3g | %.3g / %.3g | %zu / %zu | %.1f / %.1f |\n",
                s.filters[i].c_str(), m[0].low_error * 1e4, m[1].low_error * 1e4,
                m[0].low_noise * 1e4, m[1].low_noise * 1e4, m[0].low_outliers, m[1].low_outliers,
                m[0].seconds, m[1].seconds);
  }
  // A render that disagrees with the closed form by more than noise and the reference grid's
  // pre-average allow (measured at most 0.007 rms, the box's, in the full run; 0.03 with --quick)
  // means the renderer and the reference no longer image the same board: stop.
  for (size_t i = 0; i < s.filters.size(); ++i)
    for (const Measured::Mode& mode : measured[i].modes)
      if (mode.check > 0.05) {
        std::cerr << "filmback_filter_report: error: " << s.filters[i] << " renders " << mode.check
                  << " rms away from the closed form (limit 0.05)\n";
        return 1;
      }
  std::printf("\nfilter report complete\n");
  return 0;
}

}  // namespace
}  // namespace fb::filters

int main(int argc, char** argv) {
  try {
    return fb::filters::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "filmback_filter_report: error: " << e.what() << '\n';
    return 1;
  }
}
