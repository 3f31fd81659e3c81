/* app_draw: an application's points and lines (cavelight_draw_points(),
 * cavelight_draw_lines()) into the bound G-buffer, with shaders/app_geometry.vert/.frag:
 * world-space vertices, a normal each (zero: facing the eye), an albedo each, roughness
 * 0.8, no emission. The passes after the G-buffer light, shadow and tone-map them like
 * the scene. One stream buffer, refilled per call. Not here: the application's own GL
 * (cavelight_gl_proc()), the frame's passes (renderer.c). */
#ifndef CAVELIGHT_APP_DRAW_H
#define CAVELIGHT_APP_DRAW_H

#include <stddef.h>

#include "cavelight/app.h"
#include "gl/gl_functions.h"

typedef struct app_draw app_draw;

/* NULL with one line in err (the shaders). */
app_draw *app_draw_create(const gl_functions *gl, char *err, size_t errlen);
void app_draw_destroy(app_draw *a);
/* mode 0: points of size pixels, 1: lines (pairs of vertices). */
void app_draw_geometry(app_draw *a, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                       float size);

#endif
