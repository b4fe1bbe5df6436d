#include "core/film/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace fb {

std::optional<AdaptiveSettings> adaptive_settings(const AdaptiveRequest& request) {
  if (!(request.threshold > 0)) return std::nullopt;
  AdaptiveSettings s;
  // integrator.cpp: "Threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128", a guess Cycles made on
  // its test scenes.
  const uint32_t automatic = uint32_t(std::ceil(16.0 / std::pow(request.threshold, 0.3)));
  s.min_samples = std::max(4u, request.min_samples > 0 ? request.min_samples : automatic);
  // integrator.cpp: "arbitrary factor that makes the threshold more similar to what it was
  // before": the error is compared with 5 x the value Blender shows.
  s.threshold = 5.0 * request.threshold;
  return s;
}

uint32_t adaptive_check_count(const AdaptiveSettings& s, uint32_t samples_per_pixel) {
  uint32_t checks = 0;
  for (uint32_t samples = kAdaptiveStep; samples < samples_per_pixel; samples += kAdaptiveStep)
    checks += adaptive_check_due(s, samples);
  return checks;
}

ConvergenceMap::ConvergenceMap(uint32_t width, uint32_t height, const AdaptiveSettings& settings,
                               double exposure)
    : width_(width),
      height_(height),
      settings_(settings),
      exposure_(exposure),
      half_sums_(new double[size_t(width) * height * 3]()),
      half_weights_(new double[size_t(width) * height]()),
      converged_(new uint8_t[size_t(width) * height]()),
      below_(new uint8_t[size_t(width) * height]()) {}

void ConvergenceMap::add(uint32_t x, uint32_t y, uint32_t sample_index, const float* rgb,
                         float weight) {
  if (sample_index % 2 == 0) return;
  const size_t i = index(x, y);
  for (int c = 0; c < 3; ++c)
    half_sums_[3 * i + c] += double(weight) * rgb[c];
  half_weights_[i] += weight;
}

double ConvergenceMap::error(const Film& film, uint32_t x, uint32_t y) const {
  const size_t i = index(x, y), n = film.channels().size();
  const double weight = film.weights()[i], half_weight = half_weights_[i];
  if (weight == 0.0 || half_weight == 0.0) return INFINITY;  // nothing to compare yet
  double difference = 0, intensity = 0;
  for (int c = 0; c < 3; ++c) {
    const double whole = exposure_ * film.sums()[i * n + c] / weight;
    const double half = exposure_ * half_sums_[3 * i + c] / half_weight;
    difference += std::abs(whole - half);
    intensity += whole;
  }
  // adaptive_sampling.h: sqrt below 1, linear above ("R+G+B > 1 is highly exposed"); the small
  // epsilon keeps black pixels finite.
  const double normalize = intensity < 1.0 ? std::sqrt(std::max(intensity, 0.0)) : intensity;
  return difference / (1e-4 + normalize);
}

bool ConvergenceMap::below_threshold(const Film& film, uint32_t x, uint32_t y) const {
  return error(film, x, y) < settings_.threshold;
}

}  // namespace fb
