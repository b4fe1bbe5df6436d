/* The sizes of the frozen header's structs (abi_frozen/filmback/plugin_abi.h), as a C compiler lays
 * them out: abi_frozen/frozen_sizes.c fills this from that header alone, so a test that also
 * includes this filmback's header can compare the two. */
#ifndef FILMBACK_TESTS_FROZEN_SIZES_H
#define FILMBACK_TESTS_FROZEN_SIZES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct frozen_sizes {
  uint32_t plugin, camera_api, filter_api, integrator_api, hit, scene, scene_api, camera_setup;
} frozen_sizes;

frozen_sizes frozen_layout_sizes(void);

#ifdef __cplusplus
}
#endif

#endif
