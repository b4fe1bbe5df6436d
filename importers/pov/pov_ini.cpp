#include "importers/pov/pov_ini.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/util/error.h"
#include "core/util/parse_number.h"
#include "importers/pov/sdl/path_rules.h"

namespace fb::pov {
namespace fs = std::filesystem;
namespace {

// POV-Ray's own bounds on what an .ini may ask: the sides of +W/+H, +R's grid, frame numbers.
constexpr double kMaxIniImageSide = 32768;
constexpr double kMaxIniAntialiasDepth = 9;  // POV-Ray 3.7 refuses +R above 9
constexpr double kMaxIniFrame = 1e9;
constexpr double kMaxIniClock = 1e9;

std::string ini_lower(std::string_view text) {
  std::string out(text);
  for (char& ch : out)
    ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

std::string_view ini_trim(std::string_view text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return text.substr(text.size());  // still where it was
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// Options that only steer POV-Ray's window and console: nothing of the image, read silently.
bool is_console_option(const std::string& key) {
  static const char* kConsoleOptions[] = {
      "pause_when_done",    "display",          "verbose",       "test_abort",
      "test_abort_count",   "debug_console",    "fatal_console", "render_console",
      "statistic_console",  "warning_console",  "all_console",   "draw_vistas",
      "preview_start_size", "preview_end_size", "create_ini",    "version"};
  return std::any_of(std::begin(kConsoleOptions), std::end(kConsoleOptions),
                     [&](const char* name) { return key == name; });
}

// Inside `root` as written and once symbolic links are followed: the rule #include follows.
bool stays_inside(const fs::path& path, const fs::path& root) {
  return lexically_inside(path, root) && really_inside(path, root);
}

// One .ini being read: where each option comes from, for errors and warnings.
class IniReader {
 public:
  IniReader(IniOptions& out, fs::path root, std::vector<fs::path>& open_files)
      : out_(out), root_(std::move(root)), open_files_(open_files) {}

  void read(const fs::path& file, const std::string& section, const std::string& included_from) {
    file_ = file, included_from_ = included_from;
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    if (ec || !in) throw InputError(file.string() + ": error: cannot read the .ini file" + chain());
    if (bytes > kMaxIniFileBytes)
      throw InputError(file.string() + ": error: " + std::to_string(bytes) +
                       " bytes, expected an .ini of at most " + std::to_string(kMaxIniFileBytes) +
                       chain());
    const std::string wanted = ini_lower(section);
    bool found = wanted.empty(), active = true;
    std::string text;
    line_ = 0;
    while (std::getline(in, text)) {
      ++line_;
      std::string_view body = text;
      body = body.substr(0, body.find(';'));
      if (ini_trim(body).empty()) continue;
      if (ini_trim(body).front() == '[') {
        const std::string_view label = ini_trim(body);
        if (label.back() != ']')
          fail(column_of(text, label), "'" + std::string(label) + "': expected a label [Name]");
        // Labels may hold blanks and are not case sensitive (POV-Ray 3.7 manual, "INI File
        // Sections").
        active =
            !wanted.empty() && ini_lower(ini_trim(label.substr(1, label.size() - 2))) == wanted;
        found = found || active;
        continue;
      }
      if (active) read_line(text, body);
    }
    if (!found) throw InputError(file.string() + ": error: no section [" + section + "]" + chain());
  }

 private:
  static size_t column_of(const std::string& line, std::string_view part) {
    return size_t(part.data() - line.data()) + 1;
  }

  std::string where() const { return file_.string() + ":" + std::to_string(line_); }
  std::string chain() const {
    return included_from_.empty() ? "" : " (included from " + included_from_ + ")";
  }
  [[noreturn]] void fail(size_t column, const std::string& what) const {
    throw InputError(where() + ":" + std::to_string(column) + ": error: " + what + chain());
  }
  void warn(const std::string& what) { out_.warnings.push_back(where() + ": " + what); }
  void not_used(const std::string& name) {
    warn("'" + name + "': not used by filmback (docs/pov.md \".ini files\")");
  }

  // A line holds one Key=Value, or switches (+W320 -D) and .ini file names.
  void read_line(const std::string& line, std::string_view body) {
    line_text_ = &line;
    body = ini_trim(body);
    const size_t equals = body.find('=');
    const char first = body.front();
    if (equals != std::string_view::npos && first != '+' && first != '-') {
      const std::string_view key = ini_trim(body.substr(0, equals));
      std::string_view value = ini_trim(body.substr(equals + 1));
      if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
        value = value.substr(1, value.size() - 2);
      option(ini_lower(key), std::string(key), value);
      return;
    }
    std::istringstream words{std::string(body)};
    const size_t offset = size_t(body.data() - line.data());
    std::string word;
    size_t searched = 0;
    std::string body_text(body);
    while (words >> word) {
      searched = body_text.find(word, searched);
      const std::string_view value = std::string_view(line).substr(offset + searched, word.size());
      const size_t word_equals = word.find('=');
      if (word.front() == '+' || word.front() == '-')
        switch_option(word, value);
      else if (word_equals != std::string::npos)  // Key=Value among switches: "+kc declare=fp=0"
        option(ini_lower(word.substr(0, word_equals)), word.substr(0, word_equals),
               value.substr(word_equals + 1));
      else
        include(value);
      searched += word.size();
    }
  }

  size_t column(std::string_view value) const { return column_of(*line_text_, value); }

  double number(std::string_view value, const std::string& name, double lo, double hi) const {
    const std::optional<double> v = parse_number(value);
    if (!v || *v < lo || *v > hi)
      fail(column(value), name + " '" + std::string(value) + "': expected a number from " +
                              number_text(lo) + " to " + number_text(hi));
    return *v;
  }
  uint32_t whole(std::string_view value, const std::string& name, double lo, double hi) const {
    const double v = number(value, name, lo, hi);
    if (v != std::floor(v))
      fail(column(value), name + " '" + std::string(value) + "': expected a whole number");
    return uint32_t(v);
  }

  bool boolean(std::string_view value, const std::string& name) const {
    const std::string v = ini_lower(value);
    if (v == "on" || v == "true" || v == "yes" || v == "1") return true;
    if (v == "off" || v == "false" || v == "no" || v == "0") return false;
    fail(column(value),
         name + " '" + std::string(value) + "': expected on/off, true/false, yes/no or 1/0");
  }

  // A path the .ini names, relative to its folder; none unless inside the first .ini's folder
  // tree.
  std::optional<fs::path> resolve(std::string_view value) const {
    const fs::path relative{std::string(value)};
    const fs::path resolved = (file_.parent_path() / relative).lexically_normal();
    if (value.empty() || relative.is_absolute() || !stays_inside(resolved, root_))
      return std::nullopt;
    return resolved;
  }
  fs::path path(std::string_view value, const std::string& name) const {
    const std::optional<fs::path> resolved = resolve(value);
    if (!resolved)
      fail(column(value), name + " '" + std::string(value) +
                              "': expected a path inside the .ini's folder " + root_.string());
    return *resolved;
  }

  Animation& animation() { return out_.animation ? *out_.animation : out_.animation.emplace(); }

  void option(const std::string& key, const std::string& name, std::string_view value) {
    if (key == "input_file_name")
      out_.input_file = path(value, name);
    else if (key == "width")
      out_.width = whole(value, name, 1, kMaxIniImageSide);
    else if (key == "height")
      out_.height = whole(value, name, 1, kMaxIniImageSide);
    else if (key == "antialias")
      out_.antialias = boolean(value, name);
    else if (key == "antialias_threshold")
      out_.antialias_threshold = number(value, name, 0, 3);
    else if (key == "antialias_depth")
      out_.antialias_depth = whole(value, name, 1, kMaxIniAntialiasDepth);
    else if (key == "initial_frame")
      animation().initial_frame = whole_frame(value, name);
    else if (key == "final_frame")
      animation().final_frame = whole_frame(value, name);
    else if (key == "initial_clock")
      animation().initial_clock = number(value, name, -kMaxIniClock, kMaxIniClock);
    else if (key == "final_clock")
      animation().final_clock = number(value, name, -kMaxIniClock, kMaxIniClock);
    else if (key == "clock")
      out_.clock = number(value, name, -kMaxIniClock, kMaxIniClock);
    else if (key == "cyclic_animation")
      animation().cyclic = boolean(value, name);
    else if (key == "subset_start_frame")
      out_.subset_start = number(value, name, 0, kMaxIniFrame);
    else if (key == "subset_end_frame")
      out_.subset_end = number(value, name, 0, kMaxIniFrame);
    else if (key == "library_path")
      library_path(value, name);
    else if (key == "declare")
      declare(value, name);
    else if (key == "output_file_name")
      output_file(value, name);
    else if (key == "output_file_type")
      output_type(value, name);
    else if (key == "include_ini")
      include(value);
    else if (!is_console_option(key))
      not_used(name);
  }

  double whole_frame(std::string_view value, const std::string& name) const {
    const double v = number(value, name, -kMaxIniFrame, kMaxIniFrame);
    if (v != std::floor(v))
      fail(column(value), name + " '" + std::string(value) + "': expected a whole frame number");
    return v;
  }

  // Library_Path from an untrusted .ini stays inside its folder tree; a folder elsewhere is the
  // user's to give (-L), so it is skipped with a warning rather than refused.
  void library_path(std::string_view value, const std::string& name) {
    if (const std::optional<fs::path> resolved = resolve(value))
      out_.library_paths.push_back(*resolved);
    else
      warn("'" + name + "=" + std::string(value) +
           "': outside the .ini's folder, skipped (give it with -L)");
  }

  // Declare=IDENTIFIER=FLOAT (POV-Ray 3.7 manual, "Declare=IDENTIFIER=FLOAT").
  void declare(std::string_view value, const std::string& name) {
    const size_t equals = value.find('=');
    const std::string_view identifier = ini_trim(value.substr(0, equals));
    const bool valid = !identifier.empty() &&
                       !std::isdigit(static_cast<unsigned char>(identifier[0])) &&
                       std::all_of(identifier.begin(), identifier.end(), [](char ch) {
                         return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                       });
    if (equals == std::string_view::npos || !valid)
      fail(column(value), name + " '" + std::string(value) + "': expected IDENTIFIER=FLOAT");
    const std::string_view float_text = ini_trim(value.substr(equals + 1));
    out_.declarations.push_back(
        {std::string(identifier),
         number(float_text, name + " " + std::string(identifier), -1e30, 1e30)});
  }

  // Written relative to the current folder, as POV-Ray writes it, and never outside it; empty,
  // POV-Ray's default name.
  void output_file(std::string_view value, const std::string& name) {
    if (value.empty()) {
      out_.output_file.reset();
      return;
    }
    const fs::path relative{std::string(value)};
    const fs::path normal = relative.lexically_normal();
    if (relative.is_absolute() || (!normal.empty() && *normal.begin() == ".."))
      fail(column(value),
           name + " '" + std::string(value) +
               "': expected a file name relative to the current folder, without '..'");
    out_.output_file = relative;
  }

  void output_type(std::string_view value, const std::string& name) {
    if (value.empty() || !std::isalpha(static_cast<unsigned char>(value.front())))
      fail(column(value),
           name + " '" + std::string(value) + "': expected a type letter (N, E, ...)");
    out_.output_file_type = char(std::toupper(static_cast<unsigned char>(value.front())));
  }

  // Switches as on POV-Ray's command line; a '-' turns a boolean off.
  void switch_option(const std::string& word, std::string_view text) {
    const bool on = word.front() == '+';
    const std::string letters = ini_lower(word.substr(1));
    const auto rest = [&](size_t n) { return text.substr(1 + n); };
    const auto starts = [&](const char* prefix) { return letters.rfind(prefix, 0) == 0; };
    if (starts("kfi"))
      option("initial_frame", "+KFI", rest(3));
    else if (starts("kff"))
      option("final_frame", "+KFF", rest(3));
    else if (starts("kc"))
      animation().cyclic = on;
    else if (starts("ki"))
      option("initial_clock", "+KI", rest(2));
    else if (starts("kf"))
      option("final_clock", "+KF", rest(2));
    else if (starts("k"))
      option("clock", "+K", rest(1));
    else if (starts("sf"))
      option("subset_start_frame", "+SF", rest(2));
    else if (starts("ef"))
      option("subset_end_frame", "+EF", rest(2));
    else if (starts("w") && !starts("wt") && !starts("wl"))  // +WT threads, +WL warning level
      option("width", "+W", rest(1));
    else if (starts("h"))
      option("height", "+H", rest(1));
    else if (starts("r"))
      option("antialias_depth", "+R", rest(1));
    else if (starts("l"))
      option("library_path", "+L", rest(1));
    else if (starts("i"))
      option("input_file_name", "+I", rest(1));
    else if (starts("o"))
      option("output_file_name", "+O", rest(1));
    else if (starts("f")) {
      if (on && letters.size() > 1) option("output_file_type", "+F", rest(1));
    } else if (starts("a") && !starts("am") && !starts("ag")) {
      out_.antialias = on;
      if (letters.size() > 1) option("antialias_threshold", "+A", rest(1));
    } else if (starts("d") || starts("v") || starts("p") || starts("x"))
      return;  // display, verbose, pause, abort: the console's
    else
      not_used(word);
  }

  // Include_Ini=FILE, or a bare file name (".ini" assumed when none is given, as POV-Ray does).
  void include(std::string_view value) {
    fs::path file = path(value, "Include_Ini");
    if (!file.has_extension()) file += ".ini";
    const size_t at = column(value);
    if (open_files_.size() >= size_t(kMaxIniIncludeDepth))
      fail(at, "'" + std::string(value) + "': .ini files nested more than " +
                   std::to_string(kMaxIniIncludeDepth) + " deep");
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(file, ec);
    if (std::find(open_files_.begin(), open_files_.end(), real) != open_files_.end())
      fail(at, "'" + std::string(value) + "': includes itself (an .ini include cycle)");
    open_files_.push_back(real);
    IniReader nested(out_, root_, open_files_);
    nested.read(file, "",
                where() + ":" + std::to_string(at) +
                    (included_from_.empty() ? "" : ", included from " + included_from_));
    open_files_.pop_back();
  }

  IniOptions& out_;
  fs::path root_;
  std::vector<fs::path>& open_files_;
  fs::path file_;
  std::string included_from_;
  size_t line_ = 0;
  const std::string* line_text_ = nullptr;
};

}  // namespace

IniOptions read_ini(const fs::path& file, const std::string& section) {
  IniOptions out;
  fs::path root = file.parent_path().lexically_normal();
  if (root.empty()) root = ".";
  std::error_code ec;
  std::vector<fs::path> open_files{fs::weakly_canonical(file, ec)};
  IniReader(out, root, open_files).read(file, section, "");
  return out;
}

bool is_ini_argument(const std::string& argument) {
  return ini_lower(split_ini_section(argument).first.extension().string()) == ".ini";
}

std::pair<fs::path, std::string> split_ini_section(const std::string& argument) {
  const size_t open = argument.rfind('[');
  if (argument.empty() || argument.back() != ']' || open == std::string::npos)
    return {argument, ""};
  return {argument.substr(0, open), argument.substr(open + 1, argument.size() - open - 2)};
}

std::optional<IniFrames> ini_frames(const IniOptions& ini, const fs::path& file) {
  if (!ini.animation) return std::nullopt;
  const Animation& a = *ini.animation;
  IniFrames frames{int64_t(a.initial_frame), int64_t(a.final_frame)};
  if (frames.last < frames.first)
    throw InputError(file.string() + ": error: Final_Frame " + std::to_string(frames.last) +
                     " before Initial_Frame " + std::to_string(frames.first));
  // A subset written as a fraction (0.5) is that part of the sequence (POV-Ray 3.7 manual,
  // "Subsets of Animation Frames").
  const auto subset_frame = [&](double v) {
    const double count = double(frames.last - frames.first);
    return v > 0 && v < 1 ? frames.first + int64_t(std::lround(v * count)) : int64_t(v);
  };
  const IniFrames whole = frames;
  if (ini.subset_start) frames.first = std::max(frames.first, subset_frame(*ini.subset_start));
  if (ini.subset_end) frames.last = std::min(frames.last, subset_frame(*ini.subset_end));
  if (frames.last < frames.first)
    throw InputError(file.string() +
                     ": error: Subset_Start_Frame/Subset_End_Frame leave no frame of " +
                     std::to_string(whole.first) + " to " + std::to_string(whole.last));
  return frames;
}

std::optional<fs::path> ini_output_pattern(const IniOptions& ini, const fs::path& scene) {
  if (!ini.output_file) return std::nullopt;
  fs::path name = *ini.output_file;
  if (name.string().back() == '/') name /= scene.stem();
  std::string stem = (name.parent_path() / name.stem()).string();
  // POV-Ray pads the frame number to the width of Final_Frame's (allnormals01.png of 1 to 33).
  if (ini.animation) {
    const double widest =
        std::max(std::abs(ini.animation->initial_frame), std::abs(ini.animation->final_frame));
    stem += std::string(std::to_string(std::max(int64_t(widest), int64_t(1))).size(), '#');
  }
  return fs::path(stem + (ini.output_file_type == 'E' ? ".exr" : ".png"));
}

}  // namespace fb::pov
