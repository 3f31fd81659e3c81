/* preview: the master's live window of the walls unfolded (--preview), as the nodes render
 * them.
 *
 * Each update reads the images the nodes write into the session's output folder
 * (DIR/SCREEN-EYE.png: png output, local nodes or a folder the nodes share) and lays them
 * out with overview_draw(), the layout of the --overview file, then shows the picture in a
 * pixel_window scaled to fit (at most PREVIEW_MAX_SIDE pixels a side at first; the window
 * can be resized). A screen without an image yet stays black. Reading PNGs costs time, so
 * updates come at most PREVIEW_HZ times a second. Closing the window ends the preview,
 * not the session. It does not fetch images over the network: nodes on other hosts with
 * window output show nothing here. */
#ifndef CAVELIGHT_PREVIEW_H
#define CAVELIGHT_PREVIEW_H

#include <stddef.h>

#include "cluster/cluster_config.h"

#define PREVIEW_HZ 10.0
#define PREVIEW_MAX_SIDE 800

typedef struct preview preview;

/* Returns NULL with one line in err (no display, no overview offsets in the config). */
preview *preview_open(const cluster_config *cfg, const char *dir, char *err, size_t errlen);
/* Shows the newest images when PREVIEW_HZ allows it, or now with force. Returns 1 once
 * when the user closed the window (the preview stops showing), else 0. */
int preview_update(preview *p, int force);
/* How many screens the last update showed an image of. */
int preview_screens_shown(const preview *p);
/* The GLFWwindow, for tests. */
void *preview_window(preview *p);
void preview_close(preview *p);

#endif
