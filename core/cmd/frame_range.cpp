#include "core/cmd/frame_range.h"

#include <charconv>
#include <cstdio>
#include <optional>
#include <string_view>

#include "core/util/error.h"

namespace fb {
namespace {

// A whole number (an optional '-' and decimal digits) at the front of `text`, which it advances;
// nullopt if there is none or it is beyond kMaxFrameNumber.
std::optional<int64_t> take_integer(std::string_view& text) {
  int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || value < -kMaxFrameNumber || value > kMaxFrameNumber) return std::nullopt;
  text.remove_prefix(size_t(end - text.data()));
  return value;
}

// Where the last run of '#' in the file name starts and ends ([begin, end) of the path's text);
// begin == end when there is none. Blender's stringframe_chars: a slash forgets the runs before it.
std::pair<size_t, size_t> last_run(const std::string& path) {
  size_t begin = 0, end = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '/') {
      begin = end = 0;
    } else if (path[i] == '#') {
      begin = i;
      while (i < path.size() && path[i] == '#')
        ++i;
      end = i--;
    }
  }
  return {begin, end};
}

}  // namespace

std::vector<int64_t> FrameRange::frames() const {
  std::vector<int64_t> out(count());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = at(i);
  return out;
}

std::string FrameRange::text() const {
  std::string text = std::to_string(first);
  if (first == last) return text;
  text.append("-").append(std::to_string(last));
  if (step != 1) text.append(":").append(std::to_string(step));
  return text;
}

FrameRange parse_frame_range(const std::string& text, const char* option) {
  const auto fail = [&](const std::string& why) {
    return UsageError(std::string(option) + " '" + text + "': " + why);
  };
  const std::string syntax = "expected A-B[:STEP] or N, whole frame numbers from " +
                             std::to_string(-kMaxFrameNumber) + " to " +
                             std::to_string(kMaxFrameNumber);
  std::string_view rest = text;
  FrameRange range;
  const std::optional<int64_t> first = take_integer(rest);
  if (!first) throw fail(syntax);
  range.first = range.last = *first;
  if (!rest.empty()) {
    std::optional<int64_t> last;
    if (rest.front() == '-') rest.remove_prefix(1), last = take_integer(rest);
    if (!last) throw fail(syntax);
    range.last = *last;
    if (!rest.empty()) {
      std::optional<int64_t> step;
      if (rest.front() == ':') rest.remove_prefix(1), step = take_integer(rest);
      if (!step || !rest.empty()) throw fail(syntax);
      if (*step < 1) throw fail("expected a STEP of 1 or more, not " + std::to_string(*step));
      range.step = *step;
    }
  }
  if (range.last < range.first)
    throw fail("expected A <= B: the last frame " + std::to_string(range.last) +
               " is before the first " + std::to_string(range.first));
  if (range.count() > size_t(kMaxFramesInRange))
    throw fail(std::to_string(range.count()) + " frames, expected at most " +
               std::to_string(kMaxFramesInRange));
  return range;
}

bool is_frame_pattern(const std::filesystem::path& pattern) {
  const auto [begin, end] = last_run(pattern.string());
  return end > begin;
}

std::filesystem::path frame_path(const std::filesystem::path& pattern, int64_t frame) {
  const std::string text = pattern.string();
  const auto [begin, end] = last_run(text);
  if (end == begin) return pattern;
  // C's "%.*lld": at least (end - begin) digits, the sign before them, not counted among them.
  const int digits = int(end - begin);
  const long long value = frame;
  std::string number(size_t(std::snprintf(nullptr, 0, "%.*lld", digits, value)), '\0');
  std::snprintf(number.data(), number.size() + 1, "%.*lld", digits, value);
  return text.substr(0, begin) + number + text.substr(end);
}

void require_frame_pattern(const std::filesystem::path& pattern, const std::string& what) {
  if (!is_frame_pattern(pattern))
    throw UsageError(what + " '" + pattern.string() +
                     "': expected a run of '#' in the file name with --frames, replaced by each "
                     "frame's number (shot.####.exr -> shot.0012.exr)");
}

}  // namespace fb
