/* scene_transform: the placement of scene_transform.h, in double precision per point (a
 * model far from its origin loses no millimetres to float cancellation). */
#include "scene/scene_transform.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/mat4.h"

const char *const scene_up_names[SCENE_UP_COUNT] = {"y", "z"};
const char *const scene_anchor_names[SCENE_ANCHOR_COUNT] = {"auto", "camera", "centre", "none"};

/* The transform as stages: q = U p * scale - anchor, then yaw and + target, then the
 * user's rotation and + translation. */
typedef struct placement {
    int up_z;
    double scale, anchor[3], target[3], translation[3];
    float yaw[16], rotation[16];
} placement;

/* U: a Z-up file's (x, y, z) is (x, z, -y) with +y up. */
static void up(const placement *pl, const float p[3], double out[3])
{
    out[0] = p[0];
    out[1] = pl->up_z ? p[2] : p[1];
    out[2] = pl->up_z ? -(double)p[1] : p[2];
}

/* The 3x3 part of m (column-major) times v. */
static void rotate(const float m[16], const double v[3], double out[3])
{
    double r[3];
    for (int k = 0; k < 3; k++)
        r[k] = m[k] * v[0] + m[4 + k] * v[1] + m[8 + k] * v[2];
    memcpy(out, r, sizeof r);
}

static void point_d(const placement *pl, const float p[3], double out[3])
{
    double q[3];
    up(pl, p, q);
    for (int k = 0; k < 3; k++)
        q[k] = q[k] * pl->scale - pl->anchor[k];
    rotate(pl->yaw, q, q);
    for (int k = 0; k < 3; k++)
        q[k] += pl->target[k];
    rotate(pl->rotation, q, q);
    for (int k = 0; k < 3; k++)
        out[k] = q[k] + pl->translation[k];
}

static void point(const placement *pl, const float p[3], float out[3])
{
    double q[3];
    point_d(pl, p, q);
    for (int k = 0; k < 3; k++)
        out[k] = (float)q[k];
}

/* The placement as one matrix (it is affine): the images of the origin and the axes. The
 * scene keeps it (scene.placement) for what is given in the file's space: animations. */
static void placement_matrix(const placement *pl, float out[16])
{
    static const float basis[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
    double o[3], c[3];
    point_d(pl, basis[3], o);
    for (int a = 0; a < 3; a++) {
        point_d(pl, basis[a], c);
        for (int r = 0; r < 3; r++)
            out[4 * a + r] = (float)(c[r] - o[r]);
        out[4 * a + 3] = 0;
    }
    for (int r = 0; r < 3; r++)
        out[12 + r] = (float)o[r];
    out[15] = 1;
}

/* A direction (unit again; rotations and a uniform scale keep normals normal). */
static void direction(const placement *pl, const float d[3], float out[3])
{
    double q[3];
    up(pl, d, q);
    rotate(pl->yaw, q, q);
    rotate(pl->rotation, q, q);
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    for (int k = 0; k < 3; k++)
        out[k] = len > 0 ? (float)(q[k] / len) : d[k];
}

/* The bounds after U (and no scale): the box of the eight turned corners. */
static void up_bounds(const placement *pl, const scene *s, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int c = 0; c < 8; c++) {
        float corner[3];
        double q[3];
        for (int k = 0; k < 3; k++)
            corner[k] = (c >> k & 1) ? s->bounds_max[k] : s->bounds_min[k];
        up(pl, corner, q);
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], q[k]);
            hi[k] = fmax(hi[k], q[k]);
        }
    }
}

/* fit: the largest scale at which the model's extent fits the box's on every axis both
 * have (a powerwall's box is flat), standing in the middle of the box's floor. */
static int fit(placement *pl, const scene *s, const scene_stage *st, char *err, size_t errlen)
{
    double lo[3], hi[3], scale = INFINITY;
    up_bounds(pl, s, lo, hi);
    for (int k = 0; k < 3; k++) {
        double room = (double)st->box_max[k] - st->box_min[k], model = hi[k] - lo[k];
        if (room > 0 && model > 0)
            scale = fmin(scale, room / model);
    }
    if (!isfinite(scale)) {
        snprintf(err, errlen, "scene_transform.fit: the screens' box and the scene share no axis "
                 "with extent");
        return -1;
    }
    pl->scale = scale;
    for (int k = 0; k < 3; k++) {
        pl->anchor[k] = scale * (k == 1 ? lo[1] : 0.5 * (lo[k] + hi[k]));
        pl->target[k] = k == 1 ? st->box_min[1] : 0.5 * ((double)st->box_min[k] + st->box_max[k]);
    }
    return 0;
}

/* camera: the file camera's eye to home, its view turned about +y to look along -z. */
static int anchor_camera(placement *pl, const scene *s, const scene_stage *st, char *err,
                         size_t errlen)
{
    if (!s->camera.valid) {
        snprintf(err, errlen, "scene_transform.anchor: camera, but the scene has no camera "
                 "(give \"centre\" or \"none\")");
        return -1;
    }
    double eye[3], at[3];
    up(pl, s->camera.position, eye);
    up(pl, s->camera.target, at);
    double fx = at[0] - eye[0], fz = at[2] - eye[2];
    /* Ry(b) takes (fx, fz) to (0, -r) for b = atan2(fx, -fz); straight down: no turn. */
    float yaw[3] = {0, 0, 0}, zero[3] = {0, 0, 0};
    if (fx * fx + fz * fz > 1e-12 * (fx * fx + fz * fz + (at[1] - eye[1]) * (at[1] - eye[1])))
        yaw[1] = (float)(atan2(fx, -fz) * 180.0 / 3.14159265358979323846);
    mat4_from_trs_deg(zero, yaw, 1.0f, pl->yaw);
    for (int k = 0; k < 3; k++) {
        pl->anchor[k] = eye[k] * pl->scale;
        pl->target[k] = st->home[k];
    }
    return 0;
}

static int plan(placement *pl, const scene *s, const scene_transform *t, const scene_stage *st,
                char *err, size_t errlen)
{
    const float zero[3] = {0, 0, 0};
    memset(pl, 0, sizeof *pl);
    pl->up_z = t->up == SCENE_UP_Z;
    pl->scale = t->scale > 0 ? t->scale : 1.0;
    mat4_from_trs_deg(zero, zero, 1.0f, pl->yaw);
    mat4_from_trs_deg(zero, t->rotation_deg, 1.0f, pl->rotation);
    for (int k = 0; k < 3; k++)
        pl->translation[k] = t->translation[k];
    if (t->fit)
        return fit(pl, s, st, err, errlen);
    scene_anchor a = t->anchor;
    if (a == SCENE_ANCHOR_AUTO)
        a = s->camera.valid ? SCENE_ANCHOR_CAMERA : SCENE_ANCHOR_CENTRE;
    if (a == SCENE_ANCHOR_CAMERA)
        return anchor_camera(pl, s, st, err, errlen);
    if (a == SCENE_ANCHOR_CENTRE) {
        double lo[3], hi[3];
        up_bounds(pl, s, lo, hi);
        for (int k = 0; k < 3; k++)
            pl->anchor[k] = pl->scale * (k == 1 ? lo[1] : 0.5 * (lo[k] + hi[k]));
    }
    return 0;
}

static void move_camera(const placement *pl, scene_camera *c)
{
    if (!c->valid)
        return;
    point(pl, c->position, c->position);
    point(pl, c->target, c->target);
    if (c->up[0] != 0 || c->up[1] != 0 || c->up[2] != 0)
        direction(pl, c->up, c->up);
    c->ymag *= (float)pl->scale;
    c->znear *= (float)pl->scale;
    c->zfar *= (float)pl->scale;
}

int scene_transform_apply(scene *s, const scene_transform *t, const scene_stage *stage,
                          char *err, size_t errlen)
{
    placement pl;
    if (plan(&pl, s, t, stage, err, errlen) != 0)
        return -1;
    for (size_t v = 0; v < 3 * s->triangle_count; v++) {
        point(&pl, s->positions + 3 * v, s->positions + 3 * v);
        direction(&pl, s->normals + 3 * v, s->normals + 3 * v);
    }
    for (int i = 0; i < s->light_count; i++) {
        scene_light *l = &s->lights[i];
        point(&pl, l->position, l->position);
        direction(&pl, l->direction, l->direction);
        if (l->type != SCENE_LIGHT_DIRECTIONAL)
            l->intensity *= (float)(pl.scale * pl.scale);
    }
    move_camera(&pl, &s->camera);
    for (size_t i = 0; i < s->camera_count; i++)
        move_camera(&pl, &s->cameras[i]);
    float m[16];
    placement_matrix(&pl, m);
    if (s->placed)
        mat4_mul(m, s->placement, m);
    memcpy(s->placement, m, sizeof m);
    s->placed = 1;
    return 0;
}
