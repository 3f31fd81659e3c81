/* gi_rsm: a frame's reflective shadow maps as a GI method gets them, and their read-back.
 *
 * The renderer renders the maps (renderer_rsm.h) and hands every method the same gi_rsm;
 * a method that wants the texels on the host reads a layer back with a reader of its own
 * (gi_rsm_read_layer()), in one order for every method and node. Owned by no method. Not
 * here: what a method makes of the texels (vpl_source.h turns them into VPLs). */
#ifndef CAVELIGHT_GI_RSM_H
#define CAVELIGHT_GI_RSM_H

#include <stddef.h>

#include "frame/light_view.h"
#include "gl/gl_functions.h"
#include "gl/scene_gl.h"

/* This frame's maps, as the renderer rendered them. */
typedef struct gi_rsm {
    int size;                      /* texels per side */
    int layers;                    /* light views rendered, one layer each */
    const GLuint *fbo;             /* per layer: position, normal, flux in attachments 0..2 */
    GLuint textures[3];            /* the same as 2D array textures, a layer per view
                                      (renderer_rsm_textures()): for GPU passes over them */
    const light_view *views;       /* per layer: the light and view it was rendered from */
    const scene_gl *mesh;          /* the scene where the frame's objects are: a method's own
                                      maps draw it with scene_gl_draw_geometry() */
} gi_rsm;

/* A method's buffers for one read-back layer; zero-initialized is empty. */
typedef struct gi_rsm_reader {
    float *read[3];                /* position, normal (w: the texel's plane), flux */
    size_t texels;                 /* room for this many texels each */
} gi_rsm_reader;

/* Layer `layer` of rsm read back: position (w 0 where no geometry), normal with the
 * texel's plane and flux, 4 floats per texel, row by row, in r's buffers (valid until the
 * next read). Returns 0, or -1 when out of memory (nothing read). */
int gi_rsm_read_layer(gi_rsm_reader *r, const gl_functions *gl, const gi_rsm *rsm, int layer,
                      const float **position, const float **normal, const float **flux);
void gi_rsm_reader_free(gi_rsm_reader *r);

#endif
