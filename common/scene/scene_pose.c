/* scene_pose: objects' offsets, their model matrices and the file's animations
 * (scene_pose.h). */
#include "scene/scene_pose.h"

#include <math.h>
#include <string.h>

#include "base/mat4.h"

static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

void scene_pose_rest(const scene *s, scene_pose *p)
{
    memset(p, 0, sizeof *p);
    p->count = s->object_count;
    for (int o = 0; o < SCENE_MAX_OBJECTS; o++) {
        memcpy(p->offset[o], identity, sizeof identity);
        p->visible[o] = 1;
    }
}

/* Parents come before their children (scene_begin_object() takes only earlier parents),
 * so one pass in order composes every chain. */
void scene_pose_models(const scene *s, const scene_pose *p, float (*model)[16], uint8_t *shown)
{
    for (int o = 0; o < s->object_count; o++) {
        int parent = s->objects[o].parent;
        if (parent >= 0 && parent < o) {
            mat4_mul(model[parent], p->offset[o], model[o]);
            shown[o] = shown[parent] && p->visible[o];
        } else {
            memcpy(model[o], p->offset[o], sizeof model[o]);
            shown[o] = p->visible[o] != 0;
        }
    }
}

int scene_pose_object_changed(const scene *s, const scene_pose *a, const scene_pose *b, int o)
{
    for (int k = o; k >= 0 && k < s->object_count; k = s->objects[k].parent) {
        if (memcmp(a->offset[k], b->offset[k], sizeof a->offset[k]) != 0 ||
            (a->visible[k] != 0) != (b->visible[k] != 0))
            return 1;
        if (s->objects[k].parent >= k)
            break;
    }
    return 0;
}

/* ---- double-precision affine maths ----------------------------------------------- */

typedef struct dmat { double m[16]; } dmat;

static dmat dmul(dmat a, dmat b)
{
    dmat r;
    mat4d_mul(a.m, b.m, r.m);
    return r;
}

static dmat dfrom(const float m[16])
{
    dmat r;
    mat4d_from_float(m, r.m);
    return r;
}

static int dinverse(dmat a, dmat *out)
{
    return mat4_affine_inverse_d(a.m, out->m);
}

/* T * R(q) * S, q = (x, y, z, w) normalized here. */
static dmat trs(const double t[3], const double q[4], const double s[3])
{
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double x = 0, y = 0, z = 0, w = 1;
    if (len > 0 && isfinite(len)) {
        x = q[0] / len; y = q[1] / len; z = q[2] / len; w = q[3] / len;
    }
    double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                   2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                   2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)};
    dmat m = {{0}};
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++)
            m.m[c * 4 + row] = r[c * 3 + row] * s[c];
    for (int row = 0; row < 3; row++)
        m.m[12 + row] = t[row];
    m.m[15] = 1;
    return m;
}

/* ---- animation ------------------------------------------------------------------- */

static void slerp(const float *a, const float *b, double u, double out[4])
{
    double d = 0, bb[4];
    for (int k = 0; k < 4; k++)
        d += (double)a[k] * b[k];
    for (int k = 0; k < 4; k++) /* the shorter arc */
        bb[k] = d < 0 ? -(double)b[k] : b[k];
    d = fabs(d);
    double wa = 1 - u, wb = u;
    if (d < 0.9995) {
        double th = acos(d), sn = sin(th);
        wa = sin((1 - u) * th) / sn;
        wb = sin(u * th) / sn;
    }
    for (int k = 0; k < 4; k++)
        out[k] = wa * a[k] + wb * bb[k];
}

/* The channel's value at t (clamped to its keys). */
static void sample(const scene_anim_channel *c, double t, double out[4])
{
    int n = c->path == SCENE_ANIM_ROTATION ? 4 : 3;
    size_t i = 0;
    while (i + 1 < c->count && c->times[i + 1] <= t)
        i++;
    const float *a = c->values + i * (size_t)n;
    double span = i + 1 < c->count ? (double)c->times[i + 1] - c->times[i] : 0;
    double u = span > 0 ? (t - c->times[i]) / span : 0;
    if (c->step || i + 1 >= c->count || t <= c->times[0] || !(u > 0)) {
        for (int k = 0; k < n; k++)
            out[k] = a[k];
        return;
    }
    const float *b = a + n;
    if (u > 1)
        u = 1;
    if (n == 4) {
        slerp(a, b, u, out);
        return;
    }
    for (int k = 0; k < 3; k++)
        out[k] = a[k] + u * ((double)b[k] - a[k]);
}

/* offset = P W_rest L_rest^-1 L(t) W_rest^-1 P^-1: the node's animated local transform in
 * place of its rest one, as a transform of its triangles as loaded (placed by P). */
static int animated_offset(const scene *s, int o, const double t3[3], const double q[4],
                           const double s3[3], float out[16])
{
    const scene_object *ob = &s->objects[o];
    double rt[3], rq[4], rs[3];
    for (int k = 0; k < 3; k++) {
        rt[k] = ob->rest_translation[k];
        rs[k] = ob->rest_scale[k];
    }
    for (int k = 0; k < 4; k++)
        rq[k] = ob->rest_rotation[k];
    dmat place = dfrom(s->placed ? s->placement : identity), world = dfrom(ob->rest_world);
    dmat place_inv, world_inv, rest_inv;
    if (dinverse(place, &place_inv) || dinverse(world, &world_inv) ||
        dinverse(trs(rt, rq, rs), &rest_inv))
        return -1;
    dmat m = dmul(dmul(dmul(place, world), rest_inv), trs(t3, q, s3));
    m = dmul(dmul(m, world_inv), place_inv);
    for (int i = 0; i < 16; i++)
        out[i] = (float)m.m[i];
    return 0;
}

int scene_pose_animate(const scene *s, double t, scene_pose *p)
{
    if (s->anim_channel_count == 0)
        return 0;
    double d = s->anim_duration;
    t = !(t > 0) ? 0 : d > 0 ? fmod(t, d) : 0;
    int set = 0;
    for (int o = 0; o < s->object_count; o++) {
        const scene_object *ob = &s->objects[o];
        double tr[3], q[4], sc[3];
        int any = 0;
        for (int k = 0; k < 3; k++) {
            tr[k] = ob->rest_translation[k];
            sc[k] = ob->rest_scale[k];
        }
        for (int k = 0; k < 4; k++)
            q[k] = ob->rest_rotation[k];
        for (size_t c = 0; c < s->anim_channel_count; c++) {
            const scene_anim_channel *ch = &s->anim_channels[c];
            if (ch->object != o || ch->count == 0)
                continue;
            sample(ch, t, ch->path == SCENE_ANIM_TRANSLATION ? tr : ch->path == SCENE_ANIM_ROTATION ? q : sc);
            any = 1;
        }
        if (any && animated_offset(s, o, tr, q, sc, p->offset[o]) == 0)
            set++;
    }
    return set;
}
