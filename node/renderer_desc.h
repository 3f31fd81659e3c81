/* renderer_desc: what a renderer is made with (renderer.h). Types only.
 *
 * Everything the frames decide (the GI method, its settings, the RSM size, steps, medium,
 * tone mapping) comes with the frames: the renderer starts from `first` and follows them.
 * What stays here is the machine's and the caller's own: threads, whether to measure every
 * frame, where the viewer's eyes sit relative to the tracker, the bounds a cluster node
 * holds the frames' settings to. */
#ifndef CAVELIGHT_RENDERER_DESC_H
#define CAVELIGHT_RENDERER_DESC_H

#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "gi/gi_cost.h"
#include "gl/gl_functions.h"
#include "scene/scene.h"

typedef struct renderer_desc {
    const gl_functions *gl;    /* the current context's table (glctx_gl()) */
    const scene *scene;
    const frame_params *first; /* the frame it is built for (its GI method and settings, RSM
                                  size); NULL: frame_params_default() */
    int threads;               /* CPU threads of the GI methods, 0 = all cores */
    int no_reuse;              /* compute every frame pass, never reuse the last one's
                                  result, and finish GL for each stage's host ms: to
                                  measure it (benchmarks) */
    float head_to_eye[3];      /* the viewer's eye centre from the tracked head
                                  (frame_view_head_centre()): a cluster config's observer */
    const gi_limits *limits;   /* a cluster node's bounds on the frames' GI settings
                                  (gi_cost.h); NULL: none */
    /* Drawn into the G-buffer after the scene in every eye pass (an application's own
     * geometry: depth-tested against the scene's, then lit and tone-mapped like it), with
     * the G-buffer bound, its viewport set and depth test and writes on; NULL: nothing. */
    void (*gbuffer_draw)(void *user, const frame_view *view, const float view_projection[16], GLuint fbo,
                         GLuint depth_texture);
    void *gbuffer_user;
} renderer_desc;

#endif
