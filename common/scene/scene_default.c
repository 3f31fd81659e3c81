/* The built-in room: enough scene for the demo and the tests, with no files.
 *
 * x in [-2, 2] (left wall red, right wall green), y in [0, 3] (floor to ceiling),
 * z in [-2, 2] (back wall at -2). A tall blue box and a low yellow box stand on the floor,
 * a small warm emissive panel hangs on the back wall, and a spotlight near the ceiling
 * points at the floor beside the red wall, so colour bleeding is easy to see. The boxes are
 * the objects "tall_box" and "low_box" (scene_object: an application or the wand's grab
 * moves them). */
#include <stdio.h>

#include "scene/scene.h"

int scene_default_build(scene *s, char *err, size_t errlen)
{
    const scene_material mats[] = {
        {{0.75f, 0.75f, 0.75f, 1}, -1, {0, 0, 0}, 0.8f},  /* 0 white */
        {{0.80f, 0.08f, 0.06f, 1}, -1, {0, 0, 0}, 0.8f},  /* 1 red */
        {{0.08f, 0.60f, 0.10f, 1}, -1, {0, 0, 0}, 0.8f},  /* 2 green */
        {{0.15f, 0.25f, 0.70f, 1}, -1, {0, 0, 0}, 0.4f},  /* 3 blue */
        {{0.80f, 0.70f, 0.15f, 1}, -1, {0, 0, 0}, 0.6f},  /* 4 yellow */
        {{1.00f, 0.90f, 0.70f, 1}, -1, {4.0f, 3.2f, 2.0f}, 1.0f}, /* 5 warm emitter */
    };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        if (scene_add_material(s, &mats[i]) < 0)
            goto oom;

    const float X0 = -2, X1 = 2, Y0 = 0, Y1 = 3, Z0 = -2, Z1 = 2;
    const float v[8][3] = {
        {X0, Y0, Z0}, {X1, Y0, Z0}, {X1, Y0, Z1}, {X0, Y0, Z1},
        {X0, Y1, Z0}, {X1, Y1, Z0}, {X1, Y1, Z1}, {X0, Y1, Z1},
    };
    const float up[3] = {0, 1, 0}, down[3] = {0, -1, 0}, px[3] = {1, 0, 0},
                nx[3] = {-1, 0, 0}, pz[3] = {0, 0, 1}, nz[3] = {0, 0, -1};
    if (scene_add_quad(s, v[0], v[3], v[2], v[1], up, 0) ||   /* floor */
        scene_add_quad(s, v[4], v[5], v[6], v[7], down, 0) || /* ceiling */
        scene_add_quad(s, v[0], v[4], v[7], v[3], px, 1) ||   /* left wall, red */
        scene_add_quad(s, v[1], v[2], v[6], v[5], nx, 2) ||   /* right wall, green */
        scene_add_quad(s, v[0], v[1], v[5], v[4], pz, 0) ||   /* back wall */
        scene_add_quad(s, v[3], v[7], v[6], v[2], nz, 0))     /* front wall */
        goto oom;

    const float tall_lo[3] = {0.5f, 0.0f, -1.4f}, tall_hi[3] = {1.2f, 1.6f, -0.7f};
    const float low_lo[3] = {-0.6f, 0.0f, 0.2f}, low_hi[3] = {0.0f, 0.5f, 0.8f};
    if (scene_begin_object(s, "tall_box", -1) < 0 || scene_add_box(s, tall_lo, tall_hi, 0, 3) ||
        scene_begin_object(s, "low_box", -1) < 0 || scene_add_box(s, low_lo, low_hi, 0, 4))
        goto oom;
    scene_end_object(s, -1);
    /* Emissive panel 2 cm in front of the back wall, facing the room. */
    const float e0[3] = {-0.4f, 2.1f, -1.98f}, e1[3] = {0.4f, 2.1f, -1.98f},
                e2[3] = {0.4f, 2.5f, -1.98f}, e3[3] = {-0.4f, 2.5f, -1.98f};
    if (scene_add_quad(s, e0, e1, e2, e3, pz, 5))
        goto oom;

    /* Spot from near the ceiling towards the floor beside the red wall. */
    scene_light spot = {
        .position = {0.8f, 2.7f, 0.8f},
        .color = {1.0f, 0.95f, 0.85f},
        .intensity = 12.0f,
        .outer_angle = 0.55f,
        .inner_angle = 0.40f,
    };
    const float target[3] = {-2.0f, 0.4f, -0.5f};
    scene_light_aim(&spot, target);
    if (scene_add_light(s, &spot) < 0)
        goto oom;

    s->camera = (scene_camera){.valid = 1, .position = {1.3f, 1.6f, 1.9f},
                               .target = {-0.5f, 0.9f, -1.2f}, .yfov = 1.15f};
    return 0;
oom:
    snprintf(err, errlen, "default scene: out of memory");
    return -1;
}
