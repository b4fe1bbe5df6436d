// No heap allocation per ray (issue 17, goal 3): this binary replaces the global operator new
// with one that counts while armed, and intersects every kind of solid and CSG tree many times
// after a warm-up. The count must stay zero. Its own binary, so that no other test pays for the
// counting or sees the replacement.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "core/accel/solid_intersect.h"
#include "support/outline_shapes.h"
#include "support/solid_builders.h"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
// GCC inlines this into the check below and then sees free() on what operator new returned: it
// is this file's operator new, which mallocs.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop
void operator delete(void* p, std::size_t) noexcept {
  ::operator delete(p);
}

namespace fb {
namespace {

using test::ball;
using test::csg;
using test::inverted;
using test::mixed_outline;
using test::outline_solid;
using test::primitive;

// Allocations made while `work` runs.
template <class F>
long allocations_during(F work) {
  allocations = 0;
  counting = true;
  work();
  counting = false;
  return allocations;
}

TEST(SolidAllocation, TheCounterSeesAnAllocation) {
  // The replacement is in force: without it the test below would pass for nothing.
  EXPECT_EQ(allocations_during([] { ::operator delete(::operator new(16)); }), 1);
}

std::vector<Solid> solids_of_every_shape() {
  std::vector<Solid> solids;
  for (SolidKind kind : {SolidKind::kSphere, SolidKind::kBox, SolidKind::kCylinder,
                         SolidKind::kCone, SolidKind::kTorus, SolidKind::kDisc}) {
    Solid s = primitive(kind, Transform::scale({1.5, 1, 0.8}));
    s.radius0 = 1, s.radius1 = kind == SolidKind::kTorus ? 0.3 : 0.4;
    solids.push_back(s);
  }
  Solid quartic = primitive(SolidKind::kPolynomial);  // x^4 + y^4 + z^4 <= 1
  quartic.polynomial = {{1, 4, 0, 0}, {1, 0, 4, 0}, {1, 0, 0, 4}, {-1, 0, 0, 0}};
  solids.push_back(quartic);
  // A pinched superellipsoid, and a blob whose crossings (up to 4 x (8 n + 1)) outgrow the stack
  // buffer: its per-thread crossing buffers grow in the warm-up, then stay.
  Solid star = primitive(SolidKind::kSuperellipsoid, Transform::scale({1.5, 1, 0.8}));
  star.radius0 = 2.5, star.radius1 = 0.5;
  solids.push_back(star);
  Solid blob = primitive(SolidKind::kBlob);
  blob.blob.threshold = 0.5;
  for (int i = 0; i < 40; ++i) {
    const Vec3d a{std::cos(i * 0.3), std::sin(i * 0.3), i * 0.05 - 1};
    blob.blob.components.push_back({Transform(), a, a * 0.5, 0.4, i % 7 ? 1.0 : -0.5, i % 2 == 1});
  }
  solids.push_back(blob);
  // A nested difference, and a union past the stack buffer (the per-thread one).
  const Solid bite = inverted(ball({0.8, 0, 0}, 0.6, 2));
  solids.push_back(csg(SolidKind::kIntersection,
                       {csg(SolidKind::kUnion, {ball({0, 0, 0}, 1, 1), solids[4]}), bite,
                        inverted(csg(SolidKind::kIntersection, {solids[1], solids[2]}))}));
  std::vector<Solid> many;
  for (int i = 0; i < 400; ++i)
    many.push_back(ball({double(i % 20) * 0.3 - 3, double(i / 20) * 0.3 - 3, 0}, 0.1, 0));
  solids.push_back(csg(SolidKind::kUnion, many));
  // An extruded outline of every segment degree (its crossings need scratch spans), inverted.
  solids.push_back(inverted(outline_solid(mixed_outline(), Transform::scale({0.5, 0.5, 1}))));
  return solids;
}

TEST(SolidAllocation, NoneAfterWarmUp) {
  const Bounds3d reach{{-100, -100, -100}, {100, 100, 100}};
  std::vector<RenderSolid> solids;
  for (const Solid& s : solids_of_every_shape())
    solids.emplace_back(s, Transform(), reach);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3d> origins, directions;
  for (int i = 0; i < 2000; ++i) {
    origins.push_back({4 * u(rng), 4 * u(rng), 4 * u(rng)});
    directions.push_back(normalize(Vec3d{u(rng), u(rng), u(rng)} - origins.back()));
  }
  int hits = 0, inside = 0;
  const auto trace_all = [&] {
    for (const RenderSolid& solid : solids)
      for (size_t i = 0; i < origins.size(); ++i) {
        if (const auto hit = solid.first_hit(origins[i], directions[i], 0)) {
          ++hits;
          hits += bool(solid.first_hit(origins[i], directions[i], 0, hit->t * 1.5));
        }
        inside += solid.contains(origins[i] * 0.25);
      }
  };
  trace_all();  // the warm-up: the per-thread buffer grows to the big union's need
  EXPECT_EQ(allocations_during(trace_all), 0);
  EXPECT_GT(hits, 4000);  // the rays do meet the solids
  EXPECT_GT(inside, 400);
}

}  // namespace
}  // namespace fb
