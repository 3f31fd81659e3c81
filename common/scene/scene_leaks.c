/* The leak tests' scenes: single-sided, zero-thickness quads, as glTF exporters write
 * rooms, arranged so that physics leaves a region exactly black (tests/stability/
 * test_leaks.c measures how much light the rasterizer lets in; docs/stability.md).
 *
 *   leak-lid    an 8 x 8 m floor, a closed 2 x 2 x 2 m box on it (four walls and a lid,
 *               normals outward), a spot 2 m above the lid pointing down: the inside of
 *               the box gets no light at all.
 *   leak-panel  a closed 4 x 3 x 4 m room (normals inward) whose ceiling has a 1 x 1 m
 *               hole filled by an emissive panel facing down: the ceiling around the panel
 *               gets no light from it (it lies in the panel's plane), the walls and floor
 *               get the closed form of a Lambertian rectangle. No spot.
 *   leak-wall   an 8 x 3 x 4 m box (normals inward) split at x = 0 by one single-sided
 *               quad facing the lit half, a spot in the lit half pointing at the floor
 *               near the wall: the dark half gets no light at all.
 *
 * Each scene's camera looks at the region that must stay dark (or, for the panel, at the
 * ceiling and the walls). All materials are a diffuse white of albedo 0.75. */
#include <stdio.h>

#include "scene/scene.h"

static const scene_material white = {{0.75f, 0.75f, 0.75f, 1}, -1, {0, 0, 0}, 1.0f};

static int rect(scene *s, float x0, float y0, float z0, float x1, float y1, float z1,
                int facing, uint32_t material)
{
    const float lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
    return scene_add_rect(s, lo, hi, facing, material);
}

int scene_leak_lid_build(scene *s, char *err, size_t errlen)
{
    if (scene_add_material(s, &white) < 0 ||
        rect(s, -4, 0, -4, 4, 0, 4, 1, 0) ||    /* floor, also the box's bottom */
        rect(s, -1, 0, -1, 1, 2, -1, -1, 0) ||  /* box walls, normals outward */
        rect(s, -1, 0, 1, 1, 2, 1, 1, 0) ||
        rect(s, -1, 0, -1, -1, 2, 1, -1, 0) ||
        rect(s, 1, 0, -1, 1, 2, 1, 1, 0) ||
        rect(s, -1, 2, -1, 1, 2, 1, 1, 0))      /* the lid */
        goto oom;
    scene_light spot = {.position = {0, 4, 0}, .direction = {0, -1, 0}, .color = {1, 1, 1},
                        .intensity = 16.0f, .outer_angle = 0.6f, .inner_angle = 0.45f};
    if (scene_add_light(s, &spot) < 0)
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {0.8f, 1.8f, 0.8f},
                               .target = {-0.7f, 0.3f, -0.7f}, .yfov = 1.4f};
    return 0;
oom:
    snprintf(err, errlen, "leak-lid scene: out of memory");
    return -1;
}

int scene_leak_panel_build(scene *s, char *err, size_t errlen)
{
    scene_material panel = white;
    panel.emissive[0] = panel.emissive[1] = panel.emissive[2] = 4.0f;
    const float H = 3, P = 0.5f; /* ceiling height, panel half size */
    if (scene_add_material(s, &white) < 0 || scene_add_material(s, &panel) < 0 ||
        rect(s, -2, 0, -2, 2, 0, 2, 1, 0) ||    /* floor */
        rect(s, -2, 0, -2, 2, H, -2, 1, 0) ||   /* walls, normals inward */
        rect(s, -2, 0, 2, 2, H, 2, -1, 0) ||
        rect(s, -2, 0, -2, -2, H, 2, 1, 0) ||
        rect(s, 2, 0, -2, 2, H, 2, -1, 0) ||
        rect(s, -2, H, -2, 2, H, -P, -1, 0) ||  /* ceiling around the hole */
        rect(s, -2, H, P, 2, H, 2, -1, 0) ||
        rect(s, -2, H, -P, -P, H, P, -1, 0) ||
        rect(s, P, H, -P, 2, H, P, -1, 0) ||
        rect(s, -P, H, -P, P, H, P, -1, 1))     /* the panel, flush, facing down */
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {1.8f, 0.4f, 1.8f},
                               .target = {-0.6f, 2.2f, -0.6f}, .yfov = 1.4f};
    return 0;
oom:
    snprintf(err, errlen, "leak-panel scene: out of memory");
    return -1;
}

int scene_leak_wall_build(scene *s, char *err, size_t errlen)
{
    const float lo[3] = {-4, 0, -2}, hi[3] = {4, 3, 2};
    if (scene_add_material(s, &white) < 0 || scene_add_box(s, lo, hi, 1, 0) ||
        rect(s, 0, 0, -2, 0, 3, 2, -1, 0))     /* the wall, facing the lit half */
        goto oom;
    scene_light spot = {.position = {-1.0f, 2.8f, 0}, .direction = {0, -1, 0},
                        .color = {1, 1, 1}, .intensity = 12.0f, .outer_angle = 0.6f,
                        .inner_angle = 0.45f};
    const float target[3] = {-0.6f, 0, 0};
    scene_light_aim(&spot, target);
    if (scene_add_light(s, &spot) < 0)
        goto oom;
    s->camera = (scene_camera){.valid = 1, .position = {3.8f, 2.7f, 1.8f},
                               .target = {0.2f, 0.3f, -0.6f}, .yfov = 1.3f};
    return 0;
oom:
    snprintf(err, errlen, "leak-wall scene: out of memory");
    return -1;
}
