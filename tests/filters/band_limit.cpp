#include "band_limit.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

namespace fb::filters {
namespace {

using Complex = std::complex<double>;

// In-place iterative radix-2 FFT (Cooley-Tukey); inverse without the 1/n.
void fft(std::vector<Complex>& a, bool inverse) {
  const size_t n = a.size();
  for (size_t i = 1, j = 0; i < n; ++i) {  // bit-reversal permutation
    size_t bit = n >> 1;
    for (; j & bit; bit >>= 1)
      j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (size_t len = 2; len <= n; len <<= 1) {
    const double angle = 2 * std::numbers::pi / double(len) * (inverse ? 1 : -1);
    const Complex step(std::cos(angle), std::sin(angle));
    for (size_t i = 0; i < n; i += len) {
      Complex w(1);
      for (size_t k = 0; k < len / 2; ++k, w *= step) {
        const Complex u = a[i + k], v = a[i + k + len / 2] * w;
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
      }
    }
  }
}

// Low-pass of one line: mirrored to period 2n (x0..x_{n-1}, x_{n-1}..x0), so the periodic signal
// the FFT sees is continuous at the borders.
void low_pass_line(std::vector<double>& line, double cutoff) {
  const size_t n = line.size(), m = 2 * n;
  std::vector<Complex> a(m);
  for (size_t i = 0; i < n; ++i)
    a[i] = a[m - 1 - i] = line[i];
  fft(a, false);
  for (size_t k = 0; k < m; ++k) {
    const double f = double(std::min(k, m - k)) / double(m);  // cycles per sample
    a[k] *= f < cutoff ? 1.0 : f == cutoff ? 0.5 : 0.0;
  }
  fft(a, true);
  for (size_t i = 0; i < n; ++i)
    line[i] = a[i].real() / double(m);
}

template <typename Line>
void for_each_line(size_t count, size_t length, Line&& line) {
  tbb::parallel_for(size_t(0), count, [&](size_t i) {
    std::vector<double> buffer(length);
    line(i, buffer);
  });
}

}  // namespace

Grid convolve_separable(const Grid& in, const std::vector<double>& taps) {
  const auto centre = ptrdiff_t(taps.size() / 2);
  const auto pass = [&](const Grid& src, bool rows) {
    Grid out{src.width, src.height, std::vector<double>(src.values.size())};
    const size_t lines = rows ? src.height : src.width, length = rows ? src.width : src.height;
    for_each_line(lines, length, [&](size_t l, std::vector<double>&) {
      for (size_t i = 0; i < length; ++i) {
        double sum = 0;
        for (size_t t = 0; t < taps.size(); ++t) {
          const ptrdiff_t j =
              std::clamp<ptrdiff_t>(ptrdiff_t(i) - ptrdiff_t(t) + centre, 0, ptrdiff_t(length) - 1);
          sum += taps[t] * (rows ? src.at(size_t(j), l) : src.at(l, size_t(j)));
        }
        (rows ? out.at(i, l) : out.at(l, i)) = sum;
      }
    });
    return out;
  };
  return pass(pass(in, true), false);
}

Grid low_pass(const Grid& in, double cutoff) {
  for (size_t side : {in.width, in.height})
    if (side == 0 || (side & (side - 1)) != 0)
      throw std::invalid_argument("low_pass: sides must be powers of two");
  Grid out = in;
  for_each_line(out.height, out.width, [&](size_t y, std::vector<double>& line) {
    for (size_t x = 0; x < out.width; ++x)
      line[x] = out.at(x, y);
    low_pass_line(line, cutoff);
    for (size_t x = 0; x < out.width; ++x)
      out.at(x, y) = line[x];
  });
  for_each_line(out.width, out.height, [&](size_t x, std::vector<double>& line) {
    for (size_t y = 0; y < out.height; ++y)
      line[y] = out.at(x, y);
    low_pass_line(line, cutoff);
    for (size_t y = 0; y < out.height; ++y)
      out.at(x, y) = line[y];
  });
  return out;
}

}  // namespace fb::filters
