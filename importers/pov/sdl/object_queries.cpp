#include "importers/pov/sdl/object_queries.h"

#include <memory>
#include <optional>
#include <string>

#include "core/util/error.h"
#include "importers/pov/sdl/object_probe.h"

namespace fb::pov::sdl {

namespace {

// Probes kept at once: a scene that traces a fresh #local object in every loop iteration builds
// one probe per iteration; past this many, all are dropped (and built again when asked).
constexpr size_t kMaxCachedObjectProbes = 64;

Value vector_value(Vec3d v) {
  return Value::vector({v.x, v.y, v.z});
}

// The call's '(' and OBJECT argument: an object identifier, as POV-Ray requires. None when the
// object is one filmback does not convert (then reported here).
std::shared_ptr<const ObjectProbe> object_argument(Parser& p, const Tok& name) {
  const std::string& function = name.token.text;
  p.expect("(");
  const Value object = p.parse_expression();
  if (!object.get<Node>()) p.fail(function + "() expects an object identifier");
  std::shared_ptr<const ObjectProbe> probe = p.object_probe(object);
  // Answered with zeros, which the importer reports as such (its geometry is then incomplete).
  if (!probe) p.unsupported(function, p.location_of(name));
  return probe;
}

}  // namespace

std::shared_ptr<const ObjectProbe> Parser::object_probe(const Value& object) {
  const Node* node = object.get<Node>();
  if (!node || !node->object) return nullptr;
  if (auto found = object_probes_.find(object.item.get()); found != object_probes_.end())
    return found->second.probe;
  if (object_probes_.size() >= kMaxCachedObjectProbes) object_probes_.clear();
  std::shared_ptr<const ObjectProbe> probe;
  try {
    probe = std::make_shared<const ObjectProbe>(*node->object);
  } catch (const InputError& e) {
    fail(e.what());
  }
  // The entry holds the object too: its address, the key, is not reused while the entry lives.
  object_probes_[object.item.get()] = {object.item, probe};
  return probe;
}

// trace(OBJECT, A, B [, NORMAL]): the first intersection of the ray from A in direction B, and
// the surface normal there into the vector identifier NORMAL; a miss gives <0, 0, 0> and a zero
// normal, as in POV-Ray.
Value trace_function(Parser& p, const Tok& name) {
  std::shared_ptr<const ObjectProbe> probe = object_argument(p, name);
  p.expect(",");
  const Vec3d origin = p.parse_vector();
  p.expect(",");
  const Vec3d direction = p.parse_vector();
  std::optional<std::string> normal;  // the identifier's name
  if (p.accept(",")) {
    const Token identifier = p.raw_next();
    if (identifier.kind != TokenKind::kWord || !p.find(identifier.text))
      p.fail("trace(): its fourth argument must be a declared identifier, found '" +
             identifier.text + "'");
    normal = identifier.text;
  }
  p.expect(")");
  const std::optional<ProbeHit> hit = probe ? probe->trace(origin, direction) : std::nullopt;
  // Looked up again: reading the ')' may have run a directive that changed the scopes.
  if (normal) {
    if (Value* slot = p.find(*normal)) *slot = vector_value(hit ? hit->normal : Vec3d{0, 0, 0});
  }
  return vector_value(hit ? hit->position : Vec3d{0, 0, 0});
}

// inside(OBJECT, P): 1 if P is in the object's set, else 0.
Value inside_function(Parser& p, const Tok& name) {
  std::shared_ptr<const ObjectProbe> probe = object_argument(p, name);
  p.expect(",");
  const Vec3d point = p.parse_vector();
  p.expect(")");
  // Triangles have no inside here, where POV-Ray gives a height field (and a mesh with an
  // inside_vector) one: reported, as the answer may be wrong.
  if (probe && probe->has_triangles()) p.unsupported(name.token.text, p.location_of(name));
  return Value::number(probe && probe->inside(point) ? 1 : 0);
}

// min_extent(OBJECT), max_extent(OBJECT): corners of the object's bounding box.
Value extent_function(Parser& p, const Tok& name) {
  std::shared_ptr<const ObjectProbe> probe = object_argument(p, name);
  p.expect(")");
  if (!probe || probe->bounds().empty()) return vector_value({0, 0, 0});
  const Bounds3d& box = probe->bounds();
  return vector_value(name.token.text == "min_extent" ? box.lo : box.hi);
}

}  // namespace fb::pov::sdl
