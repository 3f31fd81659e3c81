/* vpl_ism: imperfect shadow maps (ISMs) for the vpl GI method (gi_vpl.h; Ritschel et al.
 * 2008 as the many-light thesis 3.3 and 4.4 builds them): the visibility of many VPLs from
 * a few points each instead of from the triangles.
 *
 * The scene is a fixed point set (common/gi/vpl/ism_points.h, uniform by area, the same on
 * every node); VPL i takes its own subset of `points` of them, projects them into the
 * paraboloid map of its hemisphere (shaders/common.glsl ism_project()), one tile of
 * size x size texels of one atlas, and keeps the nearest. Single-pixel points leave holes
 * that a pull-push pyramid fills (shaders/ism_pullpush.frag); the splat variant draws each
 * point as the disk of surface it stands for and needs no filling. Each texel of the
 * result is a record (distance / far, position, radius); shaders/shade.frag's
 * ism_visible() reads it for every VPL, behind the same seam as the exact maps.
 *
 * Not here: choosing the VPLs (gi_vpl.c) and the exact maps. GL work only; the caller
 * times and finishes it. */
#ifndef CAVELIGHT_VPL_ISM_H
#define CAVELIGHT_VPL_ISM_H

#include <stddef.h>

#include "gl/gl_functions.h"
#include "scene/scene.h"

typedef struct vpl_ism vpl_ism;

typedef struct vpl_ism_desc {
    const gl_functions *gl;
    const scene *scene;
    int size;        /* texels per side of a VPL's map: a power of two, 8..256 */
    int points;      /* points per map (vpl_settings.h: ism-points) */
    int splat;       /* 1: disks, no pull-push */
    float far;       /* distance stored as 1 */
} vpl_ism_desc;

/* NULL with one line in err. */
vpl_ism *vpl_ism_create(const vpl_ism_desc *d, char *err, size_t errlen);
void vpl_ism_destroy(vpl_ism *m);
/* The maps of VPLs 0 .. count - 1 of vpl_tex (gi_vpl.c's 3 x N texture). -1 when their
 * memory cannot be had (the VPLs are then left out). */
int vpl_ism_render(vpl_ism *m, GLuint vpl_tex, int count);
/* The maps and their uniforms (u_ism*) for the bound shading program, the atlas on unit. */
void vpl_ism_bind(const vpl_ism *m, GLuint program, int unit);
/* The final level-0 records of the atlas (4 floats per texel, row by row) into out, which
 * has room for vpl_ism_atlas_side()^2 texels: for tests. */
int vpl_ism_atlas_side(const vpl_ism *m);
void vpl_ism_read(const vpl_ism *m, float *out);

#endif
