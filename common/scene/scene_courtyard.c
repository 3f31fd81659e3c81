/* The built-in courtyard: open to the sky, so light escapes upwards instead of bouncing
 * in a closed box, and tall walls make it deep rather than wide.
 *
 * x and z in [-3, 3], y from the paving at 0 to the wall tops at 8; no roof. A spot high
 * above (standing in for the sun) lights the paving and the foot of one wall at a slant;
 * the other walls and the upper parts are lit only by light bounced off the paving. A low
 * stone basin and a hedge stand on the paving. Walls are single-sided zero-thickness
 * rectangles facing in. The camera stands in a corner looking across and up. */
#include <stdio.h>

#include "scene/scene.h"

int scene_courtyard_build(scene *s, char *err, size_t errlen)
{
    const scene_material mats[] = {
        {{0.72f, 0.60f, 0.44f, 1}, -1, {0, 0, 0}, 0.9f}, /* 0 sandstone walls */
        {{0.45f, 0.45f, 0.43f, 1}, -1, {0, 0, 0}, 0.8f}, /* 1 grey paving */
        {{0.60f, 0.60f, 0.58f, 1}, -1, {0, 0, 0}, 0.7f}, /* 2 stone basin */
        {{0.12f, 0.40f, 0.12f, 1}, -1, {0, 0, 0}, 1.0f}, /* 3 hedge */
    };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        if (scene_add_material(s, &mats[i]) < 0)
            goto oom;
    const float A = 3, H = 8;
    const float rects[][7] = {
        {-A, 0, -A, A, 0, A, 1},                        /* paving */
        {-A, 0, -A, A, H, -A, 1}, {-A, 0, A, A, H, A, -1}, /* walls, facing in */
        {-A, 0, -A, -A, H, A, 1}, {A, 0, -A, A, H, A, -1},
    };
    const uint32_t rect_mat[] = {1, 0, 0, 0, 0};
    for (size_t i = 0; i < sizeof rects / sizeof rects[0]; i++) {
        const float *r = rects[i];
        const float lo[3] = {r[0], r[1], r[2]}, hi[3] = {r[3], r[4], r[5]};
        if (scene_add_rect(s, lo, hi, (int)r[6], rect_mat[i]))
            goto oom;
    }
    const float basin0[3] = {-0.8f, 0, -0.8f}, basin1[3] = {0.8f, 0.5f, 0.8f};
    const float hedge0[3] = {1.2f, 0, -2.9f}, hedge1[3] = {2.9f, 1.1f, -1.6f};
    if (scene_add_box(s, basin0, basin1, 0, 2) || scene_add_box(s, hedge0, hedge1, 0, 3))
        goto oom;

    scene_light sun = {
        .position = {-6.0f, 18.0f, 3.0f},
        .color = {1.0f, 0.96f, 0.88f},
        .intensity = 600.0f,
        .outer_angle = 0.2f,
        .inner_angle = 0.15f,
    };
    const float target[3] = {0.8f, 0.0f, -0.6f};
    scene_light_aim(&sun, target);
    if (scene_add_light(s, &sun) < 0)
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {-2.7f, 1.6f, 2.7f},
                               .target = {1.5f, 2.6f, -2.0f}, .yfov = 1.25f};
    return 0;
oom:
    snprintf(err, errlen, "courtyard scene: out of memory");
    return -1;
}
