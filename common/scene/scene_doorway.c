/* The built-in pair of rooms: light must turn a corner.
 *
 * Room A: x in [0, 4], room B: x in [4.2, 9.2], both y in [0, 2.8] and z in [-2, 2], joined
 * by a 1 x 2.1 m doorway in the 20 cm wall between them (z in [-1.5, -0.5]). A spot near
 * room A's ceiling lights its floor away from the doorway; no direct light reaches room B,
 * which is lit only by light that bounced in room A and came through the doorway. Room
 * surfaces are single-sided zero-thickness rectangles facing in; the wall is three boxes
 * (either side of the doorway and the lintel). The camera stands in room B looking back
 * at the doorway. */
#include <stdio.h>

#include "scene/scene.h"

int scene_doorway_build(scene *s, char *err, size_t errlen)
{
    const scene_material mats[] = {
        {{0.75f, 0.74f, 0.70f, 1}, -1, {0, 0, 0}, 0.9f}, /* 0 off-white walls, ceilings */
        {{0.55f, 0.36f, 0.20f, 1}, -1, {0, 0, 0}, 0.6f}, /* 1 wooden floor, room A */
        {{0.45f, 0.55f, 0.70f, 1}, -1, {0, 0, 0}, 0.9f}, /* 2 pale blue walls, room B */
        {{0.50f, 0.50f, 0.48f, 1}, -1, {0, 0, 0}, 0.8f}, /* 3 grey floor, room B */
        {{0.70f, 0.12f, 0.10f, 1}, -1, {0, 0, 0}, 0.9f}, /* 4 red sofa in room B */
    };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        if (scene_add_material(s, &mats[i]) < 0)
            goto oom;
    const float H = 2.8f, Z0 = -2, Z1 = 2, WA = 4.0f, WB = 4.2f, X1 = 9.2f;
    const float DZ0 = -1.5f, DZ1 = -0.5f, DH = 2.1f;
    /* Room A: floor, ceiling, outer walls (the doorway wall is the boxes below). */
    const float rects[][7] = {
        {0, 0, Z0, WA, 0, Z1, 1},  {0, H, Z0, WA, H, Z1, -1}, {0, 0, Z0, 0, H, Z1, 1},
        {0, 0, Z0, WA, H, Z0, 1},  {0, 0, Z1, WA, H, Z1, -1},
        /* Room B */
        {WB, 0, Z0, X1, 0, Z1, 1}, {WB, H, Z0, X1, H, Z1, -1}, {X1, 0, Z0, X1, H, Z1, -1},
        {WB, 0, Z0, X1, H, Z0, 1}, {WB, 0, Z1, X1, H, Z1, -1},
    };
    const uint32_t rect_mat[] = {1, 0, 0, 0, 0, 3, 0, 2, 2, 2};
    for (size_t i = 0; i < sizeof rects / sizeof rects[0]; i++) {
        const float *r = rects[i];
        const float lo[3] = {r[0], r[1], r[2]}, hi[3] = {r[3], r[4], r[5]};
        if (scene_add_rect(s, lo, hi, (int)r[6], rect_mat[i]))
            goto oom;
    }
    const float w0[3] = {WA, 0, Z0}, w1[3] = {WB, H, DZ0};   /* wall before the doorway */
    const float w2[3] = {WA, 0, DZ1}, w3[3] = {WB, H, Z1};   /* wall after it */
    const float w4[3] = {WA, DH, DZ0}, w5[3] = {WB, H, DZ1}; /* lintel */
    const float sofa0[3] = {7.6f, 0, 0.4f}, sofa1[3] = {8.9f, 0.8f, 1.9f};
    if (scene_add_box(s, w0, w1, 0, 0) || scene_add_box(s, w2, w3, 0, 0) ||
        scene_add_box(s, w4, w5, 0, 0) || scene_add_box(s, sofa0, sofa1, 0, 4))
        goto oom;

    scene_light spot = {
        .position = {1.0f, 2.6f, 1.2f},
        .color = {1.0f, 0.93f, 0.8f},
        .intensity = 40.0f,
        .outer_angle = 0.5f,
        .inner_angle = 0.35f,
    };
    const float target[3] = {1.2f, 0.0f, 0.6f};
    scene_light_aim(&spot, target);
    if (scene_add_light(s, &spot) < 0)
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {8.8f, 1.7f, 1.6f},
                               .target = {4.0f, 0.9f, -1.2f}, .yfov = 1.2f};
    return 0;
oom:
    snprintf(err, errlen, "doorway scene: out of memory");
    return -1;
}
