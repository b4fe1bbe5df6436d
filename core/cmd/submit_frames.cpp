#include "core/cmd/submit_frames.h"

#include <algorithm>
#include <charconv>
#include <cstdio>

#include "core/util/error.h"

namespace fb {

namespace {

constexpr int64_t kMaxFrames = 100000;

// One integer filling [begin, end) whole; false otherwise.
bool parse_integer(const char* begin, const char* end, int64_t& value) {
  const auto [stop, ec] = std::from_chars(begin, end, value);
  return begin != end && ec == std::errc() && stop == end;
}

}  // namespace

std::vector<int64_t> parse_frame_numbers(const std::string& text, const char* option) {
  const auto bad = [&](const std::string& why) {
    return UsageError(std::string(option) + " '" + text + "': " + why);
  };
  const char* begin = text.data();
  const char* end = begin + text.size();
  const size_t colon = text.find(':');
  const char* range_end = colon == std::string::npos ? end : begin + colon;
  int64_t first = 0, last = 0, step = 1;
  // The dash between A and B is the first '-' after A's own sign.
  const std::string range(begin, range_end);
  const size_t dash = range.find('-', 1);
  const bool ok = dash == std::string::npos
                      ? parse_integer(begin, range_end, first) && (last = first, true)
                      : parse_integer(begin, begin + dash, first) &&
                            parse_integer(begin + dash + 1, range_end, last);
  if (!ok || (colon != std::string::npos && !parse_integer(range_end + 1, end, step)))
    throw bad("expected frames A-B[:STEP] or N (integers)");
  if (first > last) throw bad("the first frame is after the last");
  if (step < 1) throw bad("STEP must be at least 1");
  const int64_t count = (last - first) / step + 1;
  if (count > kMaxFrames)
    throw bad(std::to_string(count) + " frames, at most " + std::to_string(kMaxFrames));
  std::vector<int64_t> frames;
  for (int64_t i = 0; i < count; ++i)
    frames.push_back(first + i * step);
  return frames;
}

bool has_frame_pattern(const std::string& pattern) {
  const size_t name = pattern.rfind('/');
  return pattern.find('#', name == std::string::npos ? 0 : name + 1) != std::string::npos;
}

std::string with_frame_number(const std::string& pattern, int64_t frame) {
  if (!has_frame_pattern(pattern)) return pattern;
  const size_t run_end = pattern.rfind('#') + 1;
  const size_t run_begin = pattern.find_last_not_of('#', run_end - 1) + 1;  // npos + 1 == 0
  const int digits = int(std::min<size_t>(run_end - run_begin, 40));        // int64_t: 19 digits
  char number[48];
  std::snprintf(number, sizeof number, "%.*lld", digits, static_cast<long long>(frame));
  return pattern.substr(0, run_begin) + number + pattern.substr(run_end);
}

}  // namespace fb
