/* The built-in corridor: a long, narrow scene where light must travel far.
 *
 * x in [0, 12] along the corridor, y in [0, 2.6], z in [-1.2, 1.2]. A spotlight near the
 * ceiling at the near end lights an orange patch of floor and the left wall; everything
 * beyond it is lit only indirectly, which is where a few propagation steps per frame fall
 * short and reusing last frame's light (ILPV) pays. Three pillars along the right wall
 * cast indirect shadows, and the lattice fitted to this shape is about 1/20 of a cube. */
#include <stdio.h>

#include "scene/scene.h"

int scene_corridor_build(scene *s, char *err, size_t errlen)
{
    const scene_material mats[] = {
        {{0.75f, 0.75f, 0.72f, 1}, -1, {0, 0, 0}, 0.8f}, /* 0 off-white walls and ceiling */
        {{0.45f, 0.42f, 0.40f, 1}, -1, {0, 0, 0}, 0.7f}, /* 1 grey floor */
        {{0.85f, 0.40f, 0.10f, 1}, -1, {0, 0, 0}, 0.8f}, /* 2 orange rug under the spot */
        {{0.20f, 0.35f, 0.75f, 1}, -1, {0, 0, 0}, 0.5f}, /* 3 blue pillars */
        {{0.10f, 0.55f, 0.20f, 1}, -1, {0, 0, 0}, 0.8f}, /* 4 green far wall */
    };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        if (scene_add_material(s, &mats[i]) < 0)
            goto oom;

    const float lo[3] = {0, 0, -1.2f}, hi[3] = {12, 2.6f, 1.2f};
    /* The room box (inward faces), then the far wall again in green just in front of it. */
    if (scene_add_box(s, lo, hi, 1, 0))
        goto oom;
    const float floor_lo[3] = {0.0f, 0.0f, -1.2f}, floor_hi[3] = {12.0f, 0.01f, 1.2f};
    const float rug_lo[3] = {1.5f, 0.01f, -1.0f}, rug_hi[3] = {3.5f, 0.02f, 0.6f};
    const float far_lo[3] = {11.98f, 0.0f, -1.2f}, far_hi[3] = {12.0f, 2.6f, 1.2f};
    if (scene_add_box(s, floor_lo, floor_hi, 0, 1) || scene_add_box(s, rug_lo, rug_hi, 0, 2) ||
        scene_add_box(s, far_lo, far_hi, 0, 4))
        goto oom;
    for (int i = 0; i < 3; i++) {
        float x = 4.5f + 2.5f * (float)i;
        const float p_lo[3] = {x, 0.0f, 0.7f}, p_hi[3] = {x + 0.4f, 2.6f, 1.1f};
        if (scene_add_box(s, p_lo, p_hi, 0, 3))
            goto oom;
    }

    scene_light spot = {
        .position = {0.6f, 2.4f, 0.0f},
        .color = {1.0f, 0.95f, 0.85f},
        .intensity = 20.0f,
        .outer_angle = 0.6f,
        .inner_angle = 0.45f,
    };
    const float target[3] = {3.0f, 0.0f, -0.4f};
    scene_light_aim(&spot, target);
    if (scene_add_light(s, &spot) < 0)
        goto oom;

    s->camera = (scene_camera){.valid = 1, .position = {0.2f, 1.7f, 0.9f},
                               .target = {12.0f, 0.9f, -0.5f}, .yfov = 1.0f};
    return 0;
oom:
    snprintf(err, errlen, "corridor scene: out of memory");
    return -1;
}
