/* renderer_internal: state shared by renderer.c (GL passes) and renderer_lpv.c (the LPV
 * backends). Not for other modules. */
#ifndef CAVELIGHT_RENDERER_INTERNAL_H
#define CAVELIGHT_RENDERER_INTERNAL_H

#include <stddef.h>

#include "lpv/ilpv.h"
#include "lpv/lpv_classic.h"
#include "lpv/lpv_converge.h"
#include "lpv/lpv_inject.h"
#include "lpv/lpv_geometry.h"
#include "frame/light_view.h"
#include "renderer.h"
#include "base/ratelog.h"
#include "renderer_hud.h"
#include "base/workpool.h"

enum { RENDERER_QUERY_RING = 4, RENDERER_DARK_VIEWS = 16 };

/* GL timer queries read a few frames later, never waited for (paper 4.6). */
typedef struct renderer_queries {
    GLuint id[RENDERER_QUERY_RING][4];
    int pending[RENDERER_QUERY_RING];
    int next;
    long dropped;            /* implausible readings thrown away */
    double ms[4];            /* latest results that arrived */
} renderer_queries;

typedef struct renderer_draw_range {
    uint32_t material;
    GLint first;
    GLsizei count;
} renderer_draw_range;

struct renderer {
    const gl_functions *gl;
    const scene *scene;
    GLuint vao, vbo, empty_vao;
    renderer_draw_range *ranges;
    int range_count;
    GLuint *textures;

    GLuint prog_gbuffer, prog_rsm, prog_shade, prog_final;

    /* RSMs (renderer_rsm.c): one layer per light view */
    int rsm_size;
    int rsm_layers;          /* layers allocated */
    GLuint rsm_fbo[LIGHT_VIEW_MAX];
    GLuint rsm_position, rsm_normal, rsm_flux, rsm_depth;
    int view_count;          /* views rendered in the last frame pass */
    light_view views[LIGHT_VIEW_MAX];
    float *rsm_read[3];      /* position, normal, flux of one layer, read back */
    lpv_vpl *rsm_vpls;       /* renderer_rsm_vpls()'s array */
    size_t rsm_vpl_capacity;

    int eye_w, eye_h;
    GLuint gbuffer_fbo, g_position, g_normal, g_albedo, g_emissive, g_depth;
    GLuint shade_fbo, s_final, s_direct, s_indirect;
    GLuint final_fbo, f_color;
    uint8_t *rgba, *rgb;
    float *linear[3];

    /* LPV */
    renderer_lpv_backend backend;
    int gl_tiles;            /* GL propagation through shared-memory tiles */
    lattice_desc lattice;
    lpv_blockers blockers;   /* built once from the scene (lpv_geometry.h) */
    ilpv cpu;                /* incremental mode; its injection, splat and near/shell volumes
                                serve every mode and backend */
    renderer_lpv_mode mode;
    lpv_classic classic;     /* classic mode, CPU backend */
    lpv_converge converge;
    uint64_t checksum;       /* of the last computed result */
    workpool *pool;
    lpv_vpl *vpls;           /* what the LPV injects: RSM VPLs (flux / pi) and emitters */
    size_t vpl_capacity;
    lpv_vpl *emitters;       /* one VPL per emissive triangle, built at load */
    size_t emitter_count;
    double emitter_energy;
    float *upload;           /* 4 floats per cell, one colour at a time */
    GLuint lpv_tex[3];       /* what the shading samples (CPU backend) */
    uint32_t reset_epoch;
    int frames;
    lpv_inject_stats inject_stats;

    /* GL compute backend */
    GLuint prog_propagate, prog_accumulate;
    GLuint gl_near[3], gl_shell[3], gl_front[2][3], gl_blockers;
    GLuint gl_sum[3];        /* near + the chain's ages so far (classic: this frame's) */
    GLuint gl_result[3];     /* sum + w faded, composed on the host: what the shading samples */
    int gl_current;
    ilpv_history gl_history; /* the GL path's own history (ilpv_history_rule()) */
    lpv_volume gl_readback;  /* the GL path's result on the host (read back or composed) */


    renderer_hud *hud;
    frame_params frame;      /* the last frame pass's parameters, sanitized: what the eye
                                passes render */
    /* Views that show no light (renderer.c): a query over the final pass, whose shader
     * leaves black pixels out; one warning when the k-th view of a frame turns black. */
    GLuint lit_query;
    int eye_index;           /* eye passes since the frame pass */
    int view_dark[RENDERER_DARK_VIEWS];
    ratelog dark_log;
    renderer_queries frame_queries, eye_queries;
    renderer_timings timings;
    char error[256];         /* why the last eye pass failed */
};

/* renderer.c */
/* Every triangle with prog bound, its material's uniforms set per draw. */
void renderer_draw_scene(renderer *r, GLuint prog);

/* renderer_rsm.c */
int renderer_rsm_init(renderer *r, char *err, size_t errlen);
void renderer_rsm_free(renderer *r);
/* The RSM of every view of every lit light (light_views()). */
void renderer_rsm_render(renderer *r, const frame_params *p);
/* The lights, their views and shadow maps as shade.frag's uniforms (texture units given). */
void renderer_rsm_bind_shading(renderer *r, GLuint prog, const frame_params *p,
                               GLenum depth_unit, GLenum normal_unit);
/* The VPL source every GI method shares: every RSM texel a light reaches, of every view of
 * the last frame pass, as a Lambertian VPL carrying the flux it reflects, Phi in W (not
 * Phi / pi), in view then texel order (deterministic). Reads the RSMs back. The array is
 * the renderer's, valid until the next call. */
size_t renderer_rsm_vpls(renderer *r, lpv_vpl **out);

/* renderer_lpv.c */
int renderer_lpv_init(renderer *r, const renderer_desc *desc, int software, char *err, size_t errlen);
void renderer_lpv_free(renderer *r);
/* Before the RSMs: 1 if this frame reuses the last LPV result (stats updated). */
int renderer_lpv_skip(renderer *r, const frame_params *p);
/* After the RSMs are rendered: VPLs -> injection -> merge + propagation. */
uint64_t renderer_lpv_frame(renderer *r, const frame_params *p);
/* The three textures (R, G, B SH) the shading pass samples. */
void renderer_lpv_textures(const renderer *r, GLuint out[3]);


#endif
