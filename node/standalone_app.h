/* standalone_app: an application (cavelight/app.h, docs/app.md) in the standalone node,
 * without a cluster: one process is both its master and its node. Each frame runs its
 * update (the camera's head, no wand or buttons, the frame's clock at 60 Hz), commits the
 * keys it set, runs its frame, gives the renderer the objects' pose, and its draw runs in
 * every eye pass (screen "window", eye 0 for mono, -1 and +1 for a stereo pair). */
#ifndef CAVELIGHT_STANDALONE_APP_H
#define CAVELIGHT_STANDALONE_APP_H

#include <stddef.h>

#include "frame/frame_params.h"
#include "gl/glctx.h"
#include "renderer.h"
#include "scene/scene.h"

typedef struct standalone_app standalone_app;

/* Loads path and runs its init (ctx current: its GL resources), with its keys in a store
 * of the built-in keys, the scene's objects' and its own. NULL with one line in err. */
standalone_app *standalone_app_open(const char *path, const scene *sc, glctx *ctx, char *err,
                                    size_t errlen);
/* Its draw into r's eye passes. */
void standalone_app_attach(standalone_app *a, renderer *r);
/* Before frame f's passes: update, commit, frame, and the objects' pose into r. eye: the
 * eye the next eye passes draw (-1, 0, +1), set again by standalone_app_eye(). */
void standalone_app_step(standalone_app *a, renderer *r, const frame_params *fp, int f);
void standalone_app_eye(standalone_app *a, int eye);
/* Its shutdown (ctx still current), unloads. NULL is fine. */
void standalone_app_close(standalone_app *a);

#endif
