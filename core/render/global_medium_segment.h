// What the scene's global media (core/scene/global_medium.h) do to the light along one segment
// of a path, in closed form: the share of the light from behind that comes through and the
// radiance they add. Two models: POV-Ray's fog blend (Trace::ComputeFog: several fogs multiply
// their transmittances and add their colours, each fog's filter and transmit applied), and the
// physical medium it maps to (docs/pov.md, "Fog").
#pragma once

#include <vector>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/math/transform.h"
#include "core/scene/global_medium.h"

namespace fb {

struct MediumSegment {
  Rgb transmittance{1.f, 1.f, 1.f};  // multiplies the radiance from the segment's far end
  Rgb emitted{0.f, 0.f, 0.f};        // added to it, W sr^-1 m^-2
};

enum class MediumModel {
  kPovRayBlend,  // POV-Ray's: per fog, transmittance max(e^-tau, transmit) tinted by filter
  kPhysical,     // the absorbing, emitting medium: e^-(sum of tau), no filter or transmit
};

// The segment from world point `origin` along unit `direction` for `length` metres (infinite:
// a ray that escapes, which a constant fog hides completely).
MediumSegment medium_segment(const std::vector<GlobalMedium>& media, MediumModel model,
                             Vec3d origin, Vec3d direction, double length);

// The optical depth of one medium over that segment: length / distance_m for a constant fog;
// for ground fog the integral of its density, (altitude / u) (G(h_end) - G(h_start)) / distance_m
// with u the direction's component along `up` and G the density's antiderivative in h (h below 0,
// atan(h) above), or density(h_start) length / distance_m where h hardly changes.
double optical_depth(const GlobalMedium& medium, Vec3d origin, Vec3d direction, double length);

// The media as a render sees them: rays in render space (the world translated, RenderJob).
class RenderMedia {
 public:
  RenderMedia(std::vector<GlobalMedium> media, const Transform& world_from_render)
      : media_(std::move(media)), world_from_render_(world_from_render) {}
  // fb_scene_api::medium_segment: `ray` up to t_end (in units of its direction's length).
  MediumSegment along(const fb_ray& ray, float t_end, MediumModel model) const;

 private:
  std::vector<GlobalMedium> media_;
  Transform world_from_render_;
};

}  // namespace fb
