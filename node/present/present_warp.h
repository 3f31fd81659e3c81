/* present_warp: the presentation pass on one GL context: a rendered image, uploaded as it
 * comes, drawn onto its projector image through its warp_map (warp/warp_map.h) with the
 * blend maps, in shaders/present.{vert,frag}. A warp_shader is the program one context
 * shares; a warp_pass holds one viewport's textures (image, grid, maps) or mesh buffers,
 * made once from the map, which it does not keep. Draws into whatever framebuffer and
 * viewport rectangle the caller bound; knows nothing of windows or files (present.h). */
#ifndef CAVELIGHT_PRESENT_WARP_H
#define CAVELIGHT_PRESENT_WARP_H

#include <stddef.h>
#include <stdint.h>

#include "gl/gl_functions.h"
#include "warp/warp_map.h"

typedef struct warp_shader {
    const gl_functions *gl;
    GLuint program, empty_vao;
} warp_shader;

typedef struct warp_pass {
    const warp_shader *shader;
    warp_kind kind;
    int src_w, src_h, out_w, out_h;
    GLuint source, grid, alpha, beta; /* textures; 0: none */
    GLuint mesh_vao, mesh_vbo, mesh_ibo;
    int mesh_indices;
    float alpha_gamma;
    float to_cave[16];                /* WARP_POINT_GRID: the map's points to CAVE space */
} warp_pass;

/* What one draw needs beyond the pass: where, the frame's view and gamma, the mode. */
typedef struct warp_draw {
    int rect[4];               /* the projector image in the bound framebuffer: x y w h */
    const float *cave_to_clip; /* WARP_POINT_GRID: projection * view * navigation; NULL = identity */
    float display_gamma;       /* the display's decoding gamma: blending is in linear light */
    int show_blend;            /* tint the blend regions instead of blending */
} warp_draw;

int warp_shader_init(warp_shader *s, const gl_functions *gl, char *err, size_t errlen);
void warp_shader_fini(warp_shader *s);
/* map may be NULL (as rendered); to_cave: WARP_POINT_GRID's transform, NULL = identity.
 * The projector image is the map's out_w x out_h, or src_w x src_h. */
int warp_pass_init(warp_pass *p, const warp_shader *s, const warp_map *map, const float *to_cave,
                   int src_w, int src_h, char *err, size_t errlen);
void warp_pass_fini(warp_pass *p);
/* The rendered image, src_w x src_h RGB, top row first. */
void warp_pass_upload(warp_pass *p, const uint8_t *rgb);
void warp_pass_draw(const warp_pass *p, const warp_draw *d);

#endif
