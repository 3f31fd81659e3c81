#include "pose_guard.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/vec3.h"

static void grow(float lo[3], float hi[3], const float p[3])
{
    for (int i = 0; i < 3; i++) {
        lo[i] = p[i] < lo[i] ? p[i] : lo[i];
        hi[i] = p[i] > hi[i] ? p[i] : hi[i];
    }
}

static void track_init(pose_guard_track *t, const char *name, const float home[3])
{
    memset(t, 0, sizeof *t);
    t->name = name;
    t->last_good.valid = 1;
    memcpy(t->last_good.position, home, sizeof t->last_good.position);
    const float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(t->last_good.rotation, identity, sizeof identity);
}

void pose_guard_init(pose_guard *g, const cluster_config *cfg)
{
    const float *home = cfg->observer.home;
    memcpy(g->lo, home, sizeof g->lo);
    memcpy(g->hi, home, sizeof g->hi);
    for (int s = 0; s < cfg->screen_count; s++) {
        const cluster_screen *sc = &cfg->screens[s];
        float top_right[3];
        for (int i = 0; i < 3; i++)
            top_right[i] = sc->bottom_right[i] + sc->top_left[i] - sc->bottom_left[i];
        grow(g->lo, g->hi, sc->bottom_left);
        grow(g->lo, g->hi, sc->bottom_right);
        grow(g->lo, g->hi, sc->top_left);
        grow(g->lo, g->hi, top_right);
    }
    float side = 0;
    for (int i = 0; i < 3; i++)
        side = fmaxf(side, g->hi[i] - g->lo[i]);
    for (int i = 0; i < 3; i++) {
        g->lo[i] -= side;
        g->hi[i] += side;
    }
    track_init(&g->head, "head", home);
    track_init(&g->wand, "wand", home);
}

/* max |R^T R - I| over the 3x3 rotation (column-major), and its determinant. */
static float rotation_error(const float r[9], float *det)
{
    float err = 0, c12[3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            err = fmaxf(err, fabsf(vec3_dot(r + 3 * i, r + 3 * j) - (i == j ? 1.0f : 0.0f)));
    vec3_cross(r + 3, r + 6, c12);
    *det = vec3_dot(r, c12);
    return err;
}

/* The nearest right-handed orthonormal frame keeping the first column's direction. */
static void orthonormalize(float r[9])
{
    float x[3], y[3], z[3];
    memcpy(x, r, sizeof x);
    vec3_normalize(x);
    float d = vec3_dot(r + 3, x);
    for (int i = 0; i < 3; i++)
        y[i] = r[3 + i] - d * x[i];
    vec3_normalize(y);
    vec3_cross(x, y, z);
    memcpy(r, x, sizeof x);
    memcpy(r + 3, y, sizeof y);
    memcpy(r + 6, z, sizeof z);
}

static int finite_pose(const input_pose *p)
{
    for (int i = 0; i < 3; i++)
        if (!isfinite(p->position[i]))
            return 0;
    for (int i = 0; i < 9; i++)
        if (!isfinite(p->rotation[i]))
            return 0;
    return 1;
}

static void report(pose_guard_track *t, double now_ms, const char *what)
{
    uint64_t skipped;
    if (ratelog_event(&t->log, now_ms, &skipped))
        fprintf(stderr, "cavelight-master: %s pose %s (%llu replaced, %llu repaired so far; %llu not "
                "logged)\n", t->name, what, (unsigned long long)t->replaced,
                (unsigned long long)t->repaired, (unsigned long long)skipped);
}

pose_guard_result pose_guard_apply(pose_guard *g, pose_guard_track *t, input_pose *p, double now_ms)
{
    if (!p->valid)
        return POSE_GUARD_KEPT;
    char why[256] = "";
    float det = 0, err = 0;
    if (!finite_pose(p)) {
        snprintf(why, sizeof why, "pose is not finite");
    } else {
        for (int i = 0; i < 3 && !why[0]; i++)
            if (p->position[i] < g->lo[i] || p->position[i] > g->hi[i])
                snprintf(why, sizeof why, "position (%.3g, %.3g, %.3g) m lies outside the tracked space "
                         "x %.3g..%.3g, y %.3g..%.3g, z %.3g..%.3g", p->position[0], p->position[1],
                         p->position[2], g->lo[0], g->hi[0], g->lo[1], g->hi[1], g->lo[2], g->hi[2]);
        err = rotation_error(p->rotation, &det);
        if (!why[0] && (err > POSE_GUARD_ROTATION_REPAIR || !(det > 0)))
            snprintf(why, sizeof why, "rotation is no rotation (|R^T R - I| = %.3g, det %.3g)", err, det);
    }
    if (why[0]) {
        memcpy(p->position, t->last_good.position, sizeof p->position);
        memcpy(p->rotation, t->last_good.rotation, sizeof p->rotation);
        t->replaced++;
        char line[320];
        snprintf(line, sizeof line, "replaced by the last good one: the %s", why);
        report(t, now_ms, line);
        return POSE_GUARD_REPLACED;
    }
    pose_guard_result r = POSE_GUARD_KEPT;
    if (err > POSE_GUARD_ROTATION_EXACT) {
        orthonormalize(p->rotation);
        t->repaired++;
        char line[160];
        snprintf(line, sizeof line, "rotation made orthonormal (|R^T R - I| was %.3g)", err);
        report(t, now_ms, line);
        r = POSE_GUARD_REPAIRED;
    }
    t->last_good = *p;
    return r;
}
