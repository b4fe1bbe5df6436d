// POV-Ray's .ini files (docs/pov.md ".ini files"): the options that decide a render, read from an
// untrusted file as POV-Ray 3.7 reads them: `Key=Value` lines, `+W320`-style switches, `;`
// comments, `[Section]` labels, booleans as true/false/on/off/yes/no/1/0, nested .ini files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "importers/pov/pov_animation.h"

namespace fb::pov {

// Every field is unset unless the .ini sets it: the command line and filmback's defaults decide
// the rest. Paths are resolved against the folder of the .ini that names them.
struct IniOptions {
  std::optional<std::filesystem::path> input_file;  // Input_File_Name, +I
  std::optional<uint32_t> width, height;            // Width, Height, +W, +H
  std::optional<bool> antialias;                    // Antialias, +A / -A
  std::optional<double> antialias_threshold;        // Antialias_Threshold, +A0.3
  std::optional<uint32_t> antialias_depth;          // Antialias_Depth, +R
  // Initial_Frame/Final_Frame (+KFI/+KFF), Initial_Clock/Final_Clock (+KI/+KF), Cyclic_Animation
  // (+KC): set when any of them is.
  std::optional<Animation> animation;
  std::optional<double> clock;  // Clock, +K: the clock of a still
  // Subset_Start_Frame/Subset_End_Frame (+SF/+EF): a frame number, or a fraction of the sequence
  // when written with a point and between 0 and 1, as POV-Ray takes it.
  std::optional<double> subset_start, subset_end;
  std::vector<std::filesystem::path> library_paths;          // Library_Path, +L
  std::vector<std::pair<std::string, double>> declarations;  // Declare=NAME=FLOAT
  std::optional<std::filesystem::path> output_file;          // Output_File_Name, +O
  std::optional<char> output_file_type;                      // Output_File_Type, +F: 'N', 'E'...
  // "file:line: ..." for each option read but not used, and each unknown one.
  std::vector<std::string> warnings;
};

// How deep Include_Ini (or a bare file name) may nest, and how large one .ini may be.
constexpr int kMaxIniIncludeDepth = 16;
constexpr uintmax_t kMaxIniFileBytes = 1 << 20;

// Reads `file`'s unlabelled options and, when `section` is not empty, those of the section of that
// label (case-insensitive, as POV-Ray's `scene.ini[Section]`). Throws InputError
// "file:line:column: error: what was found, what was expected" (with the .ini that included it).
IniOptions read_ini(const std::filesystem::path& file, const std::string& section = {});

// "scene.ini[High]" -> {"scene.ini", "High"}; a name without a label -> {name, ""}.
std::pair<std::filesystem::path, std::string> split_ini_section(const std::string& argument);
// Whether a command line's scene names an .ini: "scene.ini", "SCENE.INI[High]".
bool is_ini_argument(const std::string& argument);

// The frames an .ini's options ask for, POV-Ray's way: Initial_Frame to Final_Frame, cut to the
// subset; none when it sets no animation. Throws InputError naming `file` for an empty subset.
struct IniFrames {
  int64_t first = 0, last = 0;
};
std::optional<IniFrames> ini_frames(const IniOptions& ini, const std::filesystem::path& file);

// The output pattern POV-Ray's Output_File_Name gives (docs/pov.md ".ini files"): the name
// without its extension, the frame number appended as '#'s as wide as Final_Frame's, then the
// extension of Output_File_Type (PNG unless it says EXR); a name ending in '/' is a folder, the
// scene's name inside it. None when the .ini names no output.
std::optional<std::filesystem::path> ini_output_pattern(const IniOptions& ini,
                                                        const std::filesystem::path& scene);

}  // namespace fb::pov
