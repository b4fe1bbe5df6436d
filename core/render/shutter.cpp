#include "core/render/shutter.h"

#include <algorithm>
#include <cmath>

#include <filmback/plugin_abi.h>

#include "core/plugin/params.h"
#include "core/util/error.h"

namespace fb {
namespace {

// Each curve shape's parameters, checked by the plugin-parameter parser (BoundParams).
const fb_param_desc kTrapezoidParams[] = {
    {"ramp", FB_PARAM_FLOAT, "0.25", "", nullptr, 0, 0.5,
     "fraction of the open interval the shutter takes to open, and again to close"}};
const fb_param_desc kTableParams[] = {
    {"values", FB_PARAM_STRING, "", "", nullptr, 0, 0,
     "relative exposure at evenly spaced times from open to close, linear in between"}};

fb_plugin shape(const char* name, const fb_param_desc* params, uint32_t count) {
  return {FB_ABI_VERSION, sizeof(fb_plugin), 0, name, "", "", params, count, nullptr};
}

// "[w0,w1,...]", each value checked by the plugin-parameter parser.
std::vector<double> parse_table(std::string_view text) {
  const fb_param_desc value{
      "values", FB_PARAM_FLOAT, "1", "", nullptr, 0, ShutterCurve::kMaxTableValue, ""};
  if (text.size() < 2 || text.front() != '[' || text.back() != ']')
    throw UsageError("values '" + std::string(text) + "': expected a bracketed list [w0,w1,...]");
  std::vector<double> values;
  std::string_view rest = text.substr(1, text.size() - 2);
  while (values.size() <= ShutterCurve::kMaxTableValues) {
    const size_t comma = rest.find(',');
    fb_value parsed;
    if (std::string expected = parse_param_value(value, rest.substr(0, comma), parsed);
        !expected.empty())
      throw UsageError("values '" + std::string(text) + "': each value must be " + expected);
    values.push_back(parsed.number[0]);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return values;
}

}  // namespace

ShutterCurve::ShutterCurve() : ShutterCurve({0, 1}, {1, 1}, "box") {}

ShutterCurve::ShutterCurve(std::vector<double> knots, std::vector<double> values,
                           std::string description)
    : knots_(std::move(knots)), values_(std::move(values)), description_(std::move(description)) {
  area_.assign(1, 0.0);
  for (size_t i = 0; i + 1 < knots_.size(); ++i)
    area_.push_back(area_.back() +
                    0.5 * (values_[i] + values_[i + 1]) * (knots_[i + 1] - knots_[i]));
}

ShutterCurve ShutterCurve::parse(std::string_view text, std::string_view option) {
  const PluginSpec spec = parse_plugin_spec(text, option);
  try {
    if (spec.name == "box") {
      BoundParams(shape("box", nullptr, 0), spec.settings);
      return ShutterCurve();
    }
    if (spec.name == "trapezoid") {
      const BoundParams params(shape("trapezoid", kTrapezoidParams, 1), spec.settings);
      const double r = params.values()[0].number[0];
      return ShutterCurve({0, r, 1 - r, 1}, {0, 1, 1, 0}, "trapezoid ramp " + number_text(r));
    }
    if (spec.name == "table") {
      const BoundParams params(shape("table", kTableParams, 1), spec.settings);
      const std::string_view text = params.values()[0].text;
      if (std::optional<ShutterCurve> curve = table(parse_table(text))) return std::move(*curve);
      throw UsageError("values '" + std::string(text) + "': " + kTableExpected);
    }
  } catch (const UsageError& e) {
    throw UsageError(std::string(option) + " '" + std::string(text) + "': " + e.what());
  }
  throw UsageError(std::string(option) + " '" + std::string(text) +
                   "': expected box, trapezoid[:ramp=R] or table:values=[w0,w1,...]");
}

std::optional<ShutterCurve> ShutterCurve::table(std::vector<double> values) {
  double sum = 0;
  for (double v : values) {
    if (!(v >= 0 && v <= kMaxTableValue)) return std::nullopt;
    sum += v;
  }
  if (values.size() < 2 || values.size() > kMaxTableValues || !(sum > 0)) return std::nullopt;
  std::vector<double> knots(values.size());
  for (size_t i = 0; i < knots.size(); ++i)
    knots[i] = double(i) / double(knots.size() - 1);
  const std::string description = "table of " + std::to_string(values.size()) + " values";
  return ShutterCurve(std::move(knots), std::move(values), description);
}

double ShutterCurve::sample(double u) const {
  const double target = std::clamp(u, 0.0, 1.0) * area_.back();
  // The segment whose area holds the target; segments of zero area are never chosen.
  const size_t i =
      std::min(size_t(std::upper_bound(area_.begin(), area_.end(), target) - area_.begin()) - 1,
               knots_.size() - 2);
  const double a = target - area_[i];
  if (!(a > 0)) return knots_[i];
  // Within the segment the curve is w(x) = w_i + k x, with area w_i x + k x^2 / 2 = a up to x:
  // x = 2a / (w_i + sqrt(w_i^2 + 2ka)), the root that stays accurate when k is near 0.
  const double h = knots_[i + 1] - knots_[i];
  const double k = (values_[i + 1] - values_[i]) / h;
  const double x =
      2 * a / (values_[i] + std::sqrt(std::max(0.0, values_[i] * values_[i] + 2 * k * a)));
  return knots_[i] + std::min(x, h);
}

double ShutterCurve::cdf(double s) const {
  s = std::clamp(s, 0.0, 1.0);
  // The segment holding s, skipping the zero-width ones a trapezoid with ramp 0 or 0.5 has.
  size_t i =
      std::min(size_t(std::upper_bound(knots_.begin(), knots_.end(), s) - knots_.begin()) - 1,
               knots_.size() - 2);
  while (i > 0 && !(knots_[i + 1] > knots_[i]))
    --i;
  const double x = s - knots_[i];
  const double k = (values_[i + 1] - values_[i]) / (knots_[i + 1] - knots_[i]);
  return (area_[i] + values_[i] * x + 0.5 * k * x * x) / area_.back();
}

double RollingShutter::fraction(double s, double row, uint32_t height_px) const {
  const double r = (std::clamp(row, 0.0, double(height_px) - 1) + 1) / double(height_px);
  return 0.5 + duration * (s - 0.5) + (1 - duration) * (r - 0.5);
}

std::string RollingShutter::description() const {
  return "rolling top to bottom, each row " + number_text(duration) + " of it";
}

}  // namespace fb
