#include "core/tessellate/csg_probe.h"

#include <cmath>

namespace fb {

namespace {

// What probing a primitive's set needs: the set alone, all of its boundary surface. A disc's set
// is its half-space (core/scene/solid.h), whose whole plane a point may lie on. The primitive is
// copied whole, so that each kind's own data (polynomial, outline, blob, sor ...) comes along.
Solid bare_set(const Solid& primitive) {
  Solid s = primitive;
  if (s.kind == SolidKind::kDisc) s.kind = SolidKind::kHalfSpace;
  s.open = s.inverse = s.bounds_only = false;
  return s;
}

// Lines probing a primitive start within the scene; half-spaces need a finite box to be
// intersected in (RenderSolid's `reach`), far beyond any scene.
constexpr double kReach = 1e12;

}  // namespace

CsgProbe::CsgProbe(const Solid& solid) {
  add(solid, true);
}

size_t CsgProbe::add(const Solid& solid, bool surface) {
  surface = surface && !solid.bounds_only;
  const size_t index = nodes_.size();
  nodes_.push_back({solid.kind, solid.inverse, kNone, {}});
  if (solid.is_primitive()) {
    nodes_[index].leaf = leaves_.size();
    leaves_.push_back({&solid,
                       RenderSolid(bare_set(solid), Transform(),
                                   {{-kReach, -kReach, -kReach}, {kReach, kReach, kReach}}),
                       surface});
    return index;
  }
  for (const Solid& child : solid.children) {
    const size_t c = add(child, surface);
    nodes_[index].children.push_back(c);
  }
  return index;
}

bool CsgProbe::contains(size_t node, Vec3d p, size_t forced, bool forced_in,
                        std::vector<int8_t>& memo) const {
  const Node& n = nodes_[node];
  bool in;
  if (n.leaf != kNone) {
    if (n.leaf == forced) {
      in = forced_in;
    } else {
      if (memo[n.leaf] < 0) memo[n.leaf] = leaves_[n.leaf].set.contains(p) ? 1 : 0;
      in = memo[n.leaf] == 1;
    }
  } else if (n.kind == SolidKind::kUnion) {
    in = false;
    for (size_t c : n.children)
      if (contains(c, p, forced, forced_in, memo)) {
        in = true;
        break;
      }
  } else {  // kIntersection
    in = true;
    for (size_t c : n.children)
      if (!contains(c, p, forced, forced_in, memo)) {
        in = false;
        break;
      }
  }
  return in != n.inverse;
}

std::array<Vec3d, 2> CsgProbe::sides(const SurfacePoint& p, double offset) {
  // Irrational to the axes and to the diagonals of boxes' faces.
  const Vec3d oblique{0.3090169943749474, 0.5590169943749474, 0.7694208842938134};
  const Vec3d beside = p.position + oblique * (0.5 * offset);
  return {beside - p.normal * offset, beside + p.normal * offset};
}

int CsgProbe::label(Vec3d point, Vec3d normal, size_t leaf, double offset) const {
  const std::array<Vec3d, 2> at = sides({point, normal}, offset);
  std::vector<int8_t> memo(leaves_.size(), -1);
  const bool with = contains(0, at[0], leaf, true, memo);
  memo.assign(leaves_.size(), -1);
  const bool without = contains(0, at[1], leaf, false, memo);
  return with == without ? 0 : with ? 1 : -1;
}

size_t CsgProbe::boundary_between(const SurfacePoint& a, const SurfacePoint& b, size_t leaf,
                                  double offset) const {
  const std::array<Vec3d, 2> at_a = sides(a, offset), at_b = sides(b, offset);
  for (int side = 0; side < 2; ++side)
    for (size_t i = 0; i < leaves_.size(); ++i)
      if (i != leaf && leaves_[i].set.contains(at_a[size_t(side)]) !=
                           leaves_[i].set.contains(at_b[size_t(side)]))
        return i;
  return kNone;
}

std::optional<CsgProbe::SurfacePoint> CsgProbe::lift(size_t leaf, Vec3d point, Vec3d direction,
                                                     double reach) const {
  const double len = length(direction);
  if (!(len > 0) || !(reach > 0)) return std::nullopt;
  const Vec3d d = direction / len;
  // The first crossing after each end of the segment, coming inwards: one of them is the crossing
  // nearest the point unless the boundary crosses the segment more than once.
  std::optional<SurfacePoint> best;
  double best_distance = reach;
  for (const double side : {-1.0, 1.0}) {
    const Vec3d origin = point + d * (side * reach);
    const std::optional<SolidHit> hit = leaves_[leaf].set.first_hit(origin, d * -side, 0);
    if (!hit) continue;
    const double distance = std::abs(hit->t - reach);
    if (distance <= best_distance) {
      best_distance = distance;
      best = SurfacePoint{hit->position, hit->normal};
    }
  }
  return best;
}

}  // namespace fb
