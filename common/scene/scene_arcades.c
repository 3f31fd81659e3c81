/* The built-in arcaded courtyard: a 12 x 24 m court open to the sky with two storeys of
 * galleries along its long sides, lit only by a lamp inside one lower gallery.
 *
 * x in [-6, 6], z in [-12, 12], y from the paving at 0 to the wall tops at 8.6. Along
 * x = -6 and x = 6 the outer walls; 2.5 m in front of them a row of eight square columns
 * (0.4 m, every 3 m) carries the upper gallery's floor slab at y = 4 and the roof slab at
 * y = 8 (0.3 m thick each), so each side has a lower gallery (0 to 4 m) and an upper one
 * (4.3 to 8 m) open to the court between the columns. The end walls close the court at
 * z = +-12. A point lamp hangs under the slab in the lower gallery at x > 0: it lights that
 * gallery's floor, back wall and ceiling directly; the court, the far galleries and the
 * upper storeys get only light that left the gallery between the columns. Thin columns
 * (less than a cell at 32 cells) and slabs whose light must leak out sideways make this
 * the hardest of the chart's scenes for a lattice. Walls are single-sided rectangles
 * facing in; columns and slabs are boxes. The camera stands in the court looking at the
 * lit gallery. */
#include <stdio.h>

#include "scene/scene.h"

enum { COLUMNS = 8 };

/* One side's gallery at x = side * (3.5 .. 6): columns, floor slab, roof slab. */
static int add_gallery(scene *s, float side, uint32_t column_mat, uint32_t slab_mat)
{
    const float inner = 3.5f, outer = 6.0f, half = 0.2f;
    for (int i = 0; i < COLUMNS; i++) {
        float z = -10.5f + 3.0f * (float)i;
        float x0 = side > 0 ? inner - half : -inner - half;
        const float lo[3] = {x0, 0.0f, z - half}, hi[3] = {x0 + 2 * half, 8.0f, z + half};
        if (scene_add_box(s, lo, hi, 0, column_mat))
            return -1;
    }
    const float slab_y[2] = {4.0f, 8.0f};
    for (int k = 0; k < 2; k++) {
        float xa = side > 0 ? inner - half : -outer, xb = side > 0 ? outer : -inner + half;
        const float lo[3] = {xa, slab_y[k], -12.0f}, hi[3] = {xb, slab_y[k] + 0.3f, 12.0f};
        if (scene_add_box(s, lo, hi, 0, slab_mat))
            return -1;
    }
    return 0;
}

int scene_arcades_build(scene *s, char *err, size_t errlen)
{
    const scene_material mats[] = {
        {{0.70f, 0.62f, 0.50f, 1}, -1, {0, 0, 0}, 0.9f}, /* 0 plastered walls */
        {{0.42f, 0.40f, 0.38f, 1}, -1, {0, 0, 0}, 0.8f}, /* 1 paving */
        {{0.75f, 0.74f, 0.70f, 1}, -1, {0, 0, 0}, 0.7f}, /* 2 limestone columns */
        {{0.60f, 0.58f, 0.55f, 1}, -1, {0, 0, 0}, 0.8f}, /* 3 slabs */
        {{0.68f, 0.30f, 0.22f, 1}, -1, {0, 0, 0}, 0.9f}, /* 4 terracotta end walls */
    };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        if (scene_add_material(s, &mats[i]) < 0)
            goto oom;
    const float X = 6, Z = 12, H = 8.6f;
    const float rects[][7] = {
        {-X, 0, -Z, X, 0, Z, 1},                          /* paving */
        {-X, 0, -Z, -X, H, Z, 1}, {X, 0, -Z, X, H, Z, -1}, /* outer walls, facing in */
        {-X, 0, -Z, X, H, -Z, 1}, {-X, 0, Z, X, H, Z, -1}, /* end walls */
    };
    const uint32_t rect_mat[] = {1, 0, 0, 4, 4};
    for (size_t i = 0; i < sizeof rects / sizeof rects[0]; i++) {
        const float *r = rects[i];
        const float lo[3] = {r[0], r[1], r[2]}, hi[3] = {r[3], r[4], r[5]};
        if (scene_add_rect(s, lo, hi, (int)r[6], rect_mat[i]))
            goto oom;
    }
    if (add_gallery(s, 1.0f, 2, 3) || add_gallery(s, -1.0f, 2, 3))
        goto oom;

    scene_light lamp = {
        .type = SCENE_LIGHT_POINT,
        .position = {4.8f, 3.3f, -3.0f},
        .direction = {0, -1, 0},
        .color = {1.0f, 0.92f, 0.78f},
        .intensity = 40.0f,
    };
    if (scene_add_light(s, &lamp) < 0)
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {-2.5f, 1.7f, 9.0f},
                               .target = {3.0f, 2.8f, -3.0f}, .yfov = 1.1f};
    return 0;
oom:
    snprintf(err, errlen, "arcades scene: out of memory");
    return -1;
}
