// POV-Ray's animation options (+KFI/+KFF, +KI/+KF, +KC), as an .ini gives them: which frames a
// sequence has and what `clock` reads at each (docs/pov.md ".ini files").
#pragma once

namespace fb::pov {

struct Animation {
  double initial_frame = 1, final_frame = 1;  // POV-Ray's defaults
  double initial_clock = 0, final_clock = 1;
  bool cyclic = false;  // Cyclic_Animation: the last frame stops one step short of final_clock

  // POV-Ray 3.7's clock_delta: the clock's step from one frame to the next (0 for one frame).
  double clock_delta() const {
    const double steps = final_frame - initial_frame + (cyclic ? 1 : 0);
    return steps > 0 ? (final_clock - initial_clock) / steps : 0;
  }
  // clock = Initial_Clock + (frame − Initial_Frame)·clock_delta (POV-Ray 3.7 manual, "Animation
  // options"; checked against `povray` +KFI/+KFF with #debug str(clock)).
  double clock_at(double frame) const {
    return initial_clock + (frame - initial_frame) * clock_delta();
  }
};

}  // namespace fb::pov
