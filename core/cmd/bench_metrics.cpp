#include "core/cmd/bench_metrics.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/util/error.h"

namespace fb {

Image colour_channels(Image image, const std::string& file) {
  const char* names[3] = {"R", "G", "B"};
  size_t index[3];
  for (int c = 0; c < 3; ++c) {
    const auto it = std::find(image.channels.begin(), image.channels.end(), names[c]);
    if (it == image.channels.end())
      throw_input(file, "", std::string("the image has no channel ") + names[c]);
    index[c] = size_t(it - image.channels.begin());
  }
  // A render's film is already R, G, B: hand its pixels on rather than keep a second copy beside
  // them (the bench's memory, docs/benchmarks.md "Issue 17").
  if (image.channels.size() == 3 && index[0] == 0 && index[1] == 1 && index[2] == 2) return image;
  Image rgb{image.width, image.height, {"R", "G", "B"}, {}};
  rgb.pixels.resize(size_t(image.width) * image.height * 3);
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
    for (int c = 0; c < 3; ++c)
      rgb.pixels[i * 3 + c] = image.pixels[i * image.channels.size() + index[c]];
  return rgb;
}

ImageError image_error(const Image& image, const Image& reference) {
  ImageError e;
  double squares = 0, relative = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const double r = reference.pixels[i];
    const double d = double(image.pixels[i]) - r;
    squares += d * d;
    relative += d * d / (r * r + kRelMseEpsilon);
    e.max_abs = std::max(e.max_abs, std::abs(d));
  }
  const double n = double(image.pixels.size());
  e.rmse = std::sqrt(squares / n);
  e.relmse = relative / n;
  return e;
}

AveragedReference average_halves(Image a, Image b) {
  const ImageError between = image_error(a, b);
  // The mean is written over `a` and the half difference over `b`, so that the halves' storage
  // becomes the reference's and no third and fourth image are made (the bench's memory).
  double relative = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = double(a.pixels[i]) - b.pixels[i];
    const float mean = 0.5f * (a.pixels[i] + b.pixels[i]);
    // relMSE's denominator is the reference's: the mean, as for every image measured against it.
    relative += d * d / 4 / (double(mean) * mean + kRelMseEpsilon);
    b.pixels[i] = 0.5f * (a.pixels[i] - b.pixels[i]);
    a.pixels[i] = mean;
  }
  AveragedReference out{std::move(a), {}, std::move(b)};
  out.noise.rmse = between.rmse / 2;
  out.noise.max_abs = between.max_abs / 2;
  out.noise.relmse = relative / double(out.image.pixels.size());
  return out;
}

ReferenceAgreement compare_references(const AveragedReference& ours,
                                      const AveragedReference& theirs) {
  ReferenceAgreement out;
  out.between = image_error(ours.image, theirs.image);
  out.noise_rmse = std::hypot(ours.noise.rmse, theirs.noise.rmse);
  Image twin = ours.image;
  for (const Image* half : {&ours.half_difference, &theirs.half_difference})
    if (half->pixels.size() == twin.pixels.size())
      for (size_t i = 0; i < twin.pixels.size(); ++i)
        twin.pixels[i] += half->pixels[i];
  out.comparison = compare_images(theirs.image, ours.image, twin);
  return out;
}

std::optional<double> LogLogFit::x_at(double error) const {
  if (!(slope < 0) || !(error > 0)) return std::nullopt;
  return std::exp((std::log(error) - intercept) / slope);
}

std::optional<LogLogFit> fit_log_log(const std::vector<double>& x,
                                     const std::vector<double>& error) {
  LogLogFit fit;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !(error[i] > 0)) continue;
    const double lx = std::log(x[i]), ly = std::log(error[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    fit.x_min = fit.points ? std::min(fit.x_min, x[i]) : x[i];
    fit.x_max = fit.points ? std::max(fit.x_max, x[i]) : x[i];
    ++fit.points;
  }
  const double n = double(fit.points);
  const double spread = sxx - sx * sx / n;
  if (fit.points < 2 || !(fit.x_max > fit.x_min) || !(spread > 0)) return std::nullopt;
  fit.slope = (sxy - sx * sy / n) / spread;
  fit.intercept = (sy - fit.slope * sx) / n;
  return fit;
}

}  // namespace fb
