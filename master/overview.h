/* overview: the unfolded CAVE in one picture.
 *
 * Reads each screen's PNG (DIR/SCREEN-EYE.png, as png-output nodes write them) and
 * places it at the screen's "overview" pixel offset from the config, on a dark canvas
 * just large enough for all of them, each labelled with its name in its top-left corner.
 * Screens without an offset are left out. The eye is "left" for stereo nodes and the node's
 * only eye otherwise. */
#ifndef CAVELIGHT_OVERVIEW_H
#define CAVELIGHT_OVERVIEW_H

#include <stddef.h>

#include "cluster/cluster_config.h"

/* Returns 0, or -1 with a one-line reason (e.g. the missing file) in err. */
int overview_compose(const cluster_config *cfg, const char *dir, const char *out_path, char *err, size_t errlen);

#endif
