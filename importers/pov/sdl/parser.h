// The SDL interpreter. Like POV-Ray's own parser it reads a token stream in which directives are
// executed as they are met: #while jumps back to its condition, a macro call pushes a frame that
// reads the macro's body, #include pushes one that reads another file. The scene grammar
// (objects.cpp, appearance.cpp, statements.cpp) and the expressions (expressions.cpp) pull
// tokens from that stream (stream.cpp, directives.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <variant>
#include <vector>

#include "core/function/user_function.h"
#include "importers/pov/pov_scene.h"
#include "importers/pov/sdl/evaluate.h"
#include "importers/pov/sdl/lexer.h"

namespace fb::pov::sdl {

// A declared object: the geometry (none when it was unsupported) and the lights it carries.
struct Node {
  std::optional<Object> object;
  std::vector<LightSource> lights;
  // The unsupported objects it holds, left out of `object`: reported when the node is placed in
  // the scene, so a declared one that is never placed leaves the geometry complete.
  std::vector<Unsupported> missing;
};

struct MaterialValue {
  std::optional<Texture> texture;
  std::optional<Interior> interior;
};

using ColourMap = std::vector<ColourMapEntry>;

using Item = std::variant<Node, Pigment, Finish, Normal, Texture, Interior, MaterialValue,
                          CameraStatement, Matrix, ColourMap, SkySphere, Media>;

struct Macro {
  std::string name;
  std::vector<std::string> params;
  std::shared_ptr<TokenFile> file;
  size_t body = 0;  // index of the first body token
  SourceLocation where;
};

struct ArrayValue;
struct ReadFile;
class ObjectProbe;  // object_probe.h

// A declared `function { ... }` (function_compiler.cpp): its compiled program, or, when it needs
// what filmback does not evaluate (a vector function, an internal(N) filmback lacks), a program
// of the same parameters that gives 0 and the feature it lacks, reported where it is used.
struct FunctionValue {
  std::shared_ptr<const UserFunction> program;
  std::string unsupported;  // empty: `program` is the function
  // A pigment function's pigment, in POV-Ray's space, colours as written; `program` is its grey.
  std::shared_ptr<const SolidPattern> pigment;
};

enum class ValueKind {
  kNone,
  kFloat,
  kVector,
  kColour,
  kString,
  kArray,
  kItem,
  kMacro,
  kFunction,
  kOpaque,
  kFile
};

struct Value {
  ValueKind kind = ValueKind::kNone;
  int dims = 1;  // kFloat 1, kVector 2..5, kColour 5
  std::array<double, 5> v{};
  std::string text;  // kString; kOpaque: what it is ("normal", "spline", ...)
  std::shared_ptr<ArrayValue> array;
  std::shared_ptr<const Item> item;
  std::shared_ptr<const Macro> macro;
  std::shared_ptr<ReadFile> file;
  std::shared_ptr<const FunctionValue> function;  // kFunction

  bool numeric() const {
    return kind == ValueKind::kFloat || kind == ValueKind::kVector || kind == ValueKind::kColour;
  }
  static Value number(double f) {
    Value value;
    value.kind = ValueKind::kFloat;
    value.v[0] = f;
    return value;
  }
  static Value vector(std::initializer_list<double> c) {
    Value value;
    value.kind = ValueKind::kVector;
    value.dims = static_cast<int>(c.size());
    int i = 0;
    for (double d : c)
      value.v[i++] = d;
    return value;
  }
  static Value colour(const Colour& c) {
    Value value;
    value.kind = ValueKind::kColour;
    value.dims = 5;
    value.v = {c.r, c.g, c.b, c.filter, c.transmit};
    return value;
  }
  static Value string(std::string s) {
    Value value;
    value.kind = ValueKind::kString;
    value.text = std::move(s);
    return value;
  }
  template <typename T>
  static Value of(T item) {
    Value value;
    value.kind = ValueKind::kItem;
    value.item = std::make_shared<const Item>(std::move(item));
    return value;
  }
  template <typename T>
  const T* get() const {
    return kind == ValueKind::kItem ? std::get_if<T>(item.get()) : nullptr;
  }
};

struct ArrayValue {
  std::vector<size_t> sizes;
  std::vector<std::optional<Value>> elements;
};

// A file opened by #fopen for reading: its tokens, read one value at a time by #read.
struct ReadFile {
  std::shared_ptr<TokenFile> tokens;
  size_t pos = 0;
};

// Where a token was read: its file's name (owned by the parser's file cache, so every token can
// carry it without copying the string) and line and column.
struct Place {
  const std::string* file = nullptr;
  uint32_t line = 0, column = 0;
  SourceLocation location() const { return {file ? *file : std::string(), line, column}; }
};

// A token with the value of the identifier it names, looked up when it was read (a macro's
// locals are gone by the time its caller uses the result).
struct Tok {
  Token token;
  bool identifier = false;
  Value value;
  const std::string* file = nullptr;  // the name of the token's file, for locations

  // string_view: the literal's length is known, so most comparisons end at the size
  bool is(TokenKind kind, std::string_view text) const {
    return token.kind == kind && token.text == text;
  }
  bool symbol(std::string_view text) const { return is(TokenKind::kSymbol, text); }
  bool word(std::string_view text) const { return !identifier && is(TokenKind::kWord, text); }
  bool keyword() const { return !identifier && token.kind == TokenKind::kWord; }
};

class Parser {
 public:
  explicit Parser(const EvaluateOptions& options);
  Scene run();

  // ---- token stream (stream.cpp) ----
  Tok next();           // the next token, directives executed, macros expanded
  const Tok& peek();    // the next token; a directive not yet executed shows as kDirective
  void unget(Tok tok);  // push back one token
  void expect(const char* symbol);
  bool accept(const char* symbol);  // consumes `symbol` if it is next
  [[noreturn]] void fail(const std::string& what) const;
  [[noreturn]] void fail_at(const SourceLocation& where, const std::string& what) const;
  SourceLocation here() const { return last_.location(); }
  SourceLocation location_of(const Tok& tok) const;
  std::string chain() const;  // " (included from ...)" for messages
  void skip_block();          // a balanced { ... } (the '{' not yet read), directives executed
  void skip_parenthesised();  // a balanced ( ... ) (the '(' not yet read)
  void unsupported(const std::string& feature, const SourceLocation& where);
  void warn(const std::string& what);
  void warn_at(const SourceLocation& where, const std::string& what);

  // ---- directives (directives.cpp) ----
  void directive(const Token& token);
  EvaluationCounts& counts() { return scene_.counts; }

  // ---- expressions (expressions.cpp) ----
  Value parse_expression();
  Value parse_rvalue();                   // anything #declare can hold
  Value index_array(const Value& array);  // after an array identifier: [i][j]...
  double parse_float();
  double parse_count();
  Vec3d parse_vector();
  Value parse_numeric(int dims);  // a float or vector promoted to `dims` components
  bool parse_bool_option();
  bool starts_value(const Tok& tok) const;  // a number, vector or colour starts at `tok`  // an
                                            // optional boolean after a flag keyword (`hollow on`)
  Colour parse_colour(bool float_fills_filter_transmit = true);
  // ---- user functions (function_compiler.cpp) ----
  FunctionValue parse_function();  // after the `function` keyword: [(params)] { body }
  // { body } of a function of `parameters`; `default_parameters`: x, y, z, which u, v also name.
  FunctionValue parse_function_body(std::vector<std::string> parameters, bool default_parameters);
  // A call of `function` at parse time, after its name: (arguments). A float, a pigment
  // function's colour, or 0 if the function is unsupported.
  Value call_function(const FunctionValue& function, const Tok& name);
  bool starts_colour(const Tok& tok) const;

  // ---- appearance (appearance.cpp) ----
  Pigment parse_pigment();            // after the `pigment` keyword
  Finish parse_finish(Finish start);  // after `finish`: changes `start`, as POV-Ray does
  Normal parse_normal();              // after the `normal` keyword
  Normal parse_normal_items(const char* closing);  // a normal's body up to `closing`
  Texture parse_texture();
  // `layer` (and the layers it carries) over `texture`'s top layer; fails past the layer limit.
  void add_texture_layer(Texture& texture, Texture layer);
  Interior parse_interior();
  // media.cpp: after `media`, `scattering` and `density` (in a media)
  Media parse_media(const Tok& keyword);
  void parse_media_scattering(Media& media);
  Colour parse_media_density(const SourceLocation& where);
  MaterialValue parse_material();
  ColourMap parse_colour_map(bool pigment_map);      // after colour_map / pigment_map
  Pigment parse_pigment_items(const char* closing);  // a pigment's body up to `closing`
  Texture parse_texture_items(const char* closing);
  void parse_pattern_arguments(const std::string& pattern);
  void parse_image_map(Pigment& p);                            // image_map.cpp: after `image_map`
  std::optional<Matrix> parse_transform_item(const Tok& tok);  // translate/rotate/.../transform
  Matrix parse_transform_block();                              // after `transform`
  const Texture& default_texture() const { return default_texture_; }

  // ---- objects (objects.cpp) ----
  bool is_object_keyword(const Tok& tok) const;
  Node parse_object(const Tok& keyword);
  Node parse_object_reference();  // object { ... }, after the '{'
  bool parse_csg_children(const std::string& keyword, const SourceLocation& where, Object& o,
                          Node& node);
  void parse_mesh(Object& o);
  void parse_mesh2(Object& o);
  void parse_polynomial(const std::string& keyword, Object& o);
  void parse_prism(Object& o);  // prism.cpp
  void parse_lathe(Object& o);  // lathe.cpp: its spline and points, after the '{'
  bool parse_text(Object& o);   // text.cpp; false: its font is not here (reported)
  void parse_height_field(
      Object& o);              // height_field.cpp: an image's or a function's, after the '{'
  void parse_blob(Object& o);  // blob.cpp: threshold and components, after the '{'
  void parse_sphere_sweep(Object& o);   // sphere_sweep.cpp: spline, spheres, tolerance
  void parse_bicubic_patch(Object& o);  // bicubic_patch.cpp: its triangles, after the '{'
  // julia_fractal.cpp: its parameter and items, after the '{'; a function it cannot render is
  // returned as what to report (the rest of the block unread), otherwise empty.
  std::string parse_julia_fractal(Object& o);
  void parse_isosurface(Object& o);  // isosurface.cpp: its function and bounds, after the '{'
  void parse_contained_by(Isosurface& container);  // isosurface.cpp: after `contained_by`
  void parse_parametric(Object& o);  // parametric.cpp: its three functions as a mesh, after '{'
  void skip_rest_of_block();         // to the '}' closing a block already open
  void parse_object_mods(Node& node);
  void parse_clipped_by(Node& node, Object& o);
  void complete_appearance(Object& o);  // after the modifiers: CSG and mesh inheritance
  void ensure_texture(Object& o);       // the object's own texture, from the #default one if none

  // ---- scene statements (statements.cpp) ----
  CameraStatement parse_camera(const Tok& keyword);
  LightSource parse_light(const Tok& keyword);
  void parse_statement(const Tok& tok);
  void parse_fog(const Tok& keyword);                 // fog.cpp: after `fog`
  void emit(Node node, const SourceLocation& where);  // a top-level object statement
  void count_objects(uint64_t n);

 private:
  struct Frame {
    std::shared_ptr<TokenFile> file;
    size_t pos = 0;
    bool macro = false;
    std::string from;              // "included from a.pov:3:1" / "in macro M called from a.pov:9:5"
    size_t cond_base = 0;          // conds_ size when the frame began
    size_t scope = 0;              // scopes_ index it pushed
    std::filesystem::path folder;  // include: the folder it was found in
    // macro parameters passed by reference: (parameter, caller's identifier)
    std::vector<std::pair<std::string, std::string>> by_reference;
  };
  enum class CondKind { kIf, kWhile, kFor, kSwitch };
  struct Cond {
    CondKind kind = CondKind::kIf;
    size_t loop_pos = 0;       // kWhile: the #while token; kFor: first body token
    std::string variable;      // kFor
    double end = 0, step = 1;  // kFor
    double switch_value = 0;   // kSwitch
    bool switch_running = false;
  };

  // stream.cpp
  const Token& raw() const;
  Tok resolve(const Token& token);
  bool pop_finished_frame();
  bool transparent_directive(const Token& token) const;
  Value* lookup(const std::string& name);
  void call_macro(const Token& name, std::shared_ptr<const Macro> macro);
  void end_macro();
  void count_token();
  void unread_pushback();

 public:
  // directives.cpp helpers used by expressions (defined(), #read)
  Value* find(const std::string& name) { return lookup(name); }
  void assign(const std::string& name, Value value, bool local);
  std::shared_ptr<TokenFile> load(const std::filesystem::path& path, const std::string& display);
  // `link_targets`: folders besides the allowed ones that a symbolic link may lead into.
  std::optional<std::filesystem::path> resolve_include(
      const std::string& name, std::filesystem::path* folder, bool scene_folder_only,
      const std::vector<std::filesystem::path>& link_targets = {}) const;
  Token raw_next();  // the next raw token of the current frame (no directives, no lookups)
  uint64_t next_random(size_t stream);
  size_t new_random_stream(double seed);
  void count_array_elements(uint64_t n);
  std::string array_limit_message() const;
  void check_string(const std::string& s);
  const EvaluateOptions& options() const { return options_; }
  // object_queries.cpp: the probe trace(), inside() and the extents ask of a declared object,
  // built at its first use; none when the object is unsupported.
  std::shared_ptr<const ObjectProbe> object_probe(const Value& object);
  int nesting = 0;  // expression/block recursion, bounded so that deep nesting cannot overflow
  // The frame address where evaluation started: Nesting also bounds the stack the recursion has
  // used, since a level's frames are several times larger in a sanitized build.
  uintptr_t stack_start = reinterpret_cast<uintptr_t>(__builtin_frame_address(0));

 private:
  // expressions.cpp, by precedence
  Value parse_ternary();
  Value parse_logic();
  Value parse_relation();
  Value parse_additive();
  Value parse_multiplicative();
  Value parse_unary();
  Value parse_postfix();
  Value parse_primary();
  int vector_level_ = -1;  // expression nesting at which '>' closes a vector literal

  // directives.cpp
  void run_directive(const Token& token);  // dispatches to one of the run_* below
  void run_if();
  void run_ifdef(bool runs_if_defined);
  void run_else(const std::string& which);
  void run_while();
  void run_for();
  void run_switch();
  void run_case(const std::string& which);
  void run_break();
  void run_undef();
  void run_version();
  void run_message(const std::string& which);
  void run_default();
  void run_fclose();
  void skip_to_branch(bool from_if_start);
  void skip_levels(int levels);
  bool parse_condition();
  void run_declare(bool local);
  void run_include();
  void run_macro_definition();
  void run_end();
  void run_switch_search();
  // file_io.cpp
  void run_fopen();
  void run_read();
  void run_write();

  EvaluateOptions options_;
  Scene scene_;
  std::filesystem::path scene_folder_;
  std::vector<Frame> frames_;
  std::vector<Cond> conds_;
  std::vector<std::unordered_map<std::string, Value>> scopes_;
  std::optional<Tok> pushback_;
  Tok peeked_directive_;
  Place last_;
  std::map<std::string, std::shared_ptr<TokenFile>> file_cache_;
  std::vector<uint32_t> random_streams_;
  Texture default_texture_;
  uint32_t macro_depth_ = 0, include_depth_ = 0;  // macro and include frames open
  // frames_.size() when the innermost running directive began (0: none): its expression ends
  // with the file it is written in.
  size_t directive_frames_ = 0;
  std::map<std::string, std::string> written_files_;  // #fopen ... write, by name
  struct CachedProbe {
    std::shared_ptr<const Item> object;
    std::shared_ptr<const ObjectProbe> probe;
  };
  std::unordered_map<const Item*, CachedProbe> object_probes_;  // by the declared object
};

// RAII bound on recursion depth (expressions in parentheses, nested blocks).
class Nesting {
 public:
  explicit Nesting(Parser& parser);
  ~Nesting() { --parser_.nesting; }

 private:
  Parser& parser_;
};

Colour to_colour(const Value& value, bool float_fills_filter_transmit);
std::string number_string(double value);  // for messages
// Moves a texture's patterns with a transform applied after it: `inverse` is the transform's
// inverse.
void transform_texture(Texture& texture, const Matrix& inverse);

}  // namespace fb::pov::sdl
