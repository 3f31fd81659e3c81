/* grab: pick the object under the wand's ray and carry it (grab.h). */
#include "grab.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"
#include "base/vec3.h"
#include "base/xalloc.h"

void grab_init(grab *g)
{
    memset(g, 0, sizeof *g);
    g->object = -1;
}

/* Brute force over the objects' triangles in their frame's models: a pick happens once per
 * press, never per frame. Static triangles hide what is behind them too. */
int grab_pick(const scene *s, const scene_pose *pose, const float origin[3], const float dir[3], float *distance)
{
    float (*model)[16] = xmalloc((size_t)(s->object_count ? s->object_count : 1) * sizeof *model);
    uint8_t shown[SCENE_MAX_OBJECTS];
    scene_pose_models(s, pose, model, shown);
    double o[3] = {origin[0], origin[1], origin[2]}, d[3] = {dir[0], dir[1], dir[2]}, best = INFINITY;
    int hit = -1;
    for (size_t t = 0; t < s->triangle_count; t++) {
        int ob = s->triangle_object ? s->triangle_object[t] : -1;
        if (ob >= 0 && !shown[ob])
            continue;
        double v[3][3];
        for (int k = 0; k < 3; k++) {
            float p[3];
            if (ob >= 0)
                mat4_transform_point(model[ob], s->positions + 9 * t + 3 * k, p);
            else
                memcpy(p, s->positions + 9 * t + 3 * k, sizeof p);
            for (int a = 0; a < 3; a++)
                v[k][a] = p[a];
        }
        double dist = vec3d_ray_triangle(o, d, v[0], v[1], v[2]);
        if (dist > 0 && dist < best) {
            best = dist;
            hit = ob;
        }
    }
    free(model);
    if (hit >= 0 && distance)
        *distance = (float)best;
    return hit;
}

int grab_update(grab *g, const scene *s, scene_pose *pose, const frame_params *f, const input_state *in,
                int active)
{
    int held = active && in->wand.valid && (in->buttons & (1u << INPUT_BUTTON_C));
    if (!held || s->object_count == 0) {
        g->object = -1;
        return 0;
    }
    float wand[16], world[16];
    input_pose_to_mat4(&in->wand, wand);
    mat4_mul(f->navigation, wand, world);
    if (g->object < 0) {
        if (!(in->pressed & (1u << INPUT_BUTTON_C)))
            return 0; /* held since before the layout: no pick */
        const float origin[3] = {world[12], world[13], world[14]};
        float dir[3] = {-world[8], -world[9], -world[10]};
        float len = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (int k = 0; k < 3 && len > 0; k++)
            dir[k] /= len;
        g->object = len > 0 ? grab_pick(s, pose, origin, dir, NULL) : -1;
        if (g->object < 0)
            return 0;
        float (*model)[16] = xmalloc((size_t)s->object_count * sizeof *model);
        uint8_t shown[SCENE_MAX_OBJECTS];
        scene_pose_models(s, pose, model, shown);
        memcpy(g->model_start, model[g->object], sizeof g->model_start);
        memcpy(g->wand_start, world, sizeof g->wand_start);
        free(model);
        return 1;
    }
    /* model = W_now W_start^-1 model_start; offset = parent_model^-1 model. */
    float inv[16], m[16], parent_inv[16];
    if (mat4_affine_inverse(g->wand_start, inv) != 0)
        return 1;
    mat4_mul(world, inv, m);
    mat4_mul(m, g->model_start, m);
    int parent = s->objects[g->object].parent;
    if (parent >= 0) {
        float (*model)[16] = xmalloc((size_t)s->object_count * sizeof *model);
        uint8_t shown[SCENE_MAX_OBJECTS];
        scene_pose_models(s, pose, model, shown);
        int ok = mat4_affine_inverse(model[parent], parent_inv) == 0;
        free(model);
        if (!ok)
            return 1;
        mat4_mul(parent_inv, m, m);
    }
    memcpy(pose->offset[g->object], m, sizeof m);
    return 1;
}
