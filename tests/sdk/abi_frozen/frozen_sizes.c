/* frozen_sizes.h from the frozen header: the quoted include finds abi_frozen/filmback/ first,
 * beside this file, whatever include path the test binary has. */
#include "filmback/plugin_abi.h"

#include "../frozen_sizes.h"

frozen_sizes frozen_layout_sizes(void) {
  frozen_sizes s;
  s.plugin = sizeof(fb_plugin);
  s.camera_api = sizeof(fb_camera_api);
  s.filter_api = sizeof(fb_filter_api);
  s.integrator_api = sizeof(fb_integrator_api);
  s.hit = sizeof(fb_hit);
  s.scene = sizeof(fb_scene);
  s.scene_api = sizeof(fb_scene_api);
  s.camera_setup = sizeof(fb_camera_setup);
  return s;
}
