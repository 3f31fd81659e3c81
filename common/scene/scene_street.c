/* The built-in street block: an open square tens of metres across among buildings, lit by
 * a low sun, the kind of scene the high-res RSM paper was made for (its urban street with
 * coloured planes for colour bleeding).
 *
 * A 48 x 48 m paved ground (y = 0) with eight buildings around a square of about 24 x 20 m,
 * 6 to 16 m tall (boxes, outward faces, no roofs' details); in the square a red and a
 * green panel (3 x 4 m, 15 cm thick) stand in the sun and tint the facades and paving
 * next to them, and a low stone wall runs across. The sun is a directional light 20
 * degrees above the horizon from the south-west, so the buildings cast long shadows and
 * half the square is lit only indirectly. No roof, no enclosing walls: light escapes to
 * the sky. The camera stands at eye height at the square's south edge looking north-east
 * across it. */
#include <math.h>
#include <stdio.h>

#include "scene/scene.h"

int scene_street_build(scene *s, char *err, size_t errlen)
{
    const scene_material mats[] = {
        {{0.30f, 0.30f, 0.30f, 1}, -1, {0, 0, 0}, 0.9f}, /* 0 asphalt and paving */
        {{0.70f, 0.62f, 0.50f, 1}, -1, {0, 0, 0}, 0.9f}, /* 1 sandstone */
        {{0.75f, 0.75f, 0.73f, 1}, -1, {0, 0, 0}, 0.8f}, /* 2 white render */
        {{0.55f, 0.32f, 0.25f, 1}, -1, {0, 0, 0}, 0.9f}, /* 3 brick */
        {{0.80f, 0.12f, 0.10f, 1}, -1, {0, 0, 0}, 0.6f}, /* 4 red panel */
        {{0.12f, 0.70f, 0.20f, 1}, -1, {0, 0, 0}, 0.6f}, /* 5 green panel */
        {{0.55f, 0.55f, 0.52f, 1}, -1, {0, 0, 0}, 0.9f}, /* 6 stone wall */
    };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        if (scene_add_material(s, &mats[i]) < 0)
            goto oom;
    const float ground_lo[3] = {-24, 0, -24}, ground_hi[3] = {24, 0, 24};
    if (scene_add_rect(s, ground_lo, ground_hi, 1, 0))
        goto oom;
    /* x0, z0, x1, z1, height, material */
    const float buildings[][6] = {
        {-24, -24, -12, -10, 14, 1}, {-10, -24, 4, -12, 10, 2}, {6, -24, 24, -14, 16, 3},
        {14, -12, 24, 4, 8, 2},      {12, 8, 24, 24, 12, 1},    {-4, 12, 10, 24, 6, 3},
        {-24, 10, -8, 24, 9, 2},     {-24, -6, -14, 6, 12, 3},
    };
    for (size_t i = 0; i < sizeof buildings / sizeof buildings[0]; i++) {
        const float *b = buildings[i];
        const float lo[3] = {b[0], 0, b[1]}, hi[3] = {b[2], b[4], b[3]};
        if (scene_add_box(s, lo, hi, 0, (uint32_t)b[5]))
            goto oom;
    }
    const float red_lo[3] = {-4, 0, -2}, red_hi[3] = {-1, 4, -1.85f};
    const float green_lo[3] = {5, 0, -4}, green_hi[3] = {5.15f, 4, -1};
    const float wall_lo[3] = {-8, 0, 4}, wall_hi[3] = {6, 0.9f, 4.4f};
    if (scene_add_box(s, red_lo, red_hi, 0, 4) || scene_add_box(s, green_lo, green_hi, 0, 5) ||
        scene_add_box(s, wall_lo, wall_hi, 0, 6))
        goto oom;
    /* The sun 20 degrees up, from the south-west (-x, +z), travelling north-east. */
    const float up = 20.0f * 3.14159265f / 180.0f, az = 0.7071f;
    scene_light sun = {
        .position = {-20, 20, 20}, /* where the HUD shows it */
        .direction = {cosf(up) * az, -sinf(up), -cosf(up) * az},
        .color = {1.0f, 0.92f, 0.80f},
        .intensity = 3.0f,
        .type = SCENE_LIGHT_DIRECTIONAL,
    };
    if (scene_add_light(s, &sun) < 0)
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {-2, 1.7f, 10},
                               .target = {4, 3.5f, -10}, .yfov = 1.1f};
    return 0;
oom:
    snprintf(err, errlen, "street scene: out of memory");
    return -1;
}
