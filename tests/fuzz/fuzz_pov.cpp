// libFuzzer harness: a POV-Ray scene through the whole importer (import_scene: lexer, parser and
// evaluator, then the conversion into filmback's Scene), with a library folder, files to #include
// and #fopen beside the scene, a symbolic link out of the scene's folder and a file outside every
// allowed folder. The evaluator's limits are a hundredth of the defaults or less, so that one
// input costs milliseconds; what is fuzzed is that every limit is met with an error, not the
// limits' values. Any exception other than the importer's own errors is a finding.
#include "core/util/error.h"
#include "importers/import_scene.h"
#include "tests/fuzz/scratch_folder.h"

namespace {

const fb::fuzz::ScratchFolder& folder() {
  static const fb::fuzz::ScratchFolder f("pov");
  static const bool filled = [] {
    f.write("scene/local.inc", "#declare Local = sphere { 0, 1 }\n");
    f.write("scene/sub/near.inc", "#local Near = 2; #declare FromSub = Near * 2;\n");
    f.write("scene/data.txt", "1, -2.5, <3, 4, 5>, \"text\",\n");
    f.write("lib/lib.inc",
            "#macro Lib(A) box { -A, A } #end\n#declare LibColor = rgb <1, 0.5, 0>;\n");
    f.write("outside.inc", "#error \"outside.inc must never be read\"\n");
    f.link("scene/link.inc", "../outside.inc");
    return true;
  }();
  (void)filled;
  return f;
}

fb::ImportOptions options() {
  fb::ImportOptions o;
  o.resolution = std::pair{64u, 48u};
  o.library_paths = {folder().root() / "lib"};
  o.pov_limits.tokens = 50'000;
  o.pov_limits.loop_iterations = 5'000;
  o.pov_limits.array_elements = 10'000;
  o.pov_limits.objects = 2'000;
  o.pov_limits.string_bytes = 4096;
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const fb::ImportOptions kOptions = options();
  const auto scene = folder().write("scene/scene.pov", data, size);
  fb::Diagnostics diagnostics;
  try {
    fb::import_scene(scene, kOptions, diagnostics);
  } catch (const fb::InputError&) {
  } catch (const fb::UsageError&) {
  }
  return 0;
}
