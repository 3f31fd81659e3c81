#include "gi/caches/cache_light.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

static const float PI_F = 3.14159265358979f;
/* shaders/common.glsl's SPECULAR_F0: the dielectric reflectance at normal incidence. */
static const float CACHE_SPECULAR_F0 = 0.04f;

/* The running sums of one proxy. */
typedef struct proxy_sums {
    float e[3], sw, m1[3], m2[3], seen, all, plain;
} proxy_sums;

/* The lobe that weighs each VAL: none (diffuse), or f_s at the cache towards view. */
typedef struct lobe {
    const float *view;   /* unit, towards the eye; NULL: diffuse */
    float m;             /* specular exponent */
} lobe;

static void gather(const light_cache *c, const vpl *vals, size_t n, const uint8_t *visible,
                   const lobe *l, proxy_sums *s)
{
    memset(s, 0, sizeof *s);
    for (size_t j = 0; j < n; j++) {
        const vpl *v = &vals[j];
        float d[3];
        vec3_sub(v->position, c->position, d);
        float r2 = vec3_dot(d, d);
        if (!(r2 > 0.0f))
            continue;
        float cos_c = vec3_dot(c->normal, d), cos_l = -vec3_dot(v->normal, d);
        if (!(cos_c > 0.0f && cos_l > 0.0f))
            continue;
        float k = cos_c * cos_l / (r2 * (v->area + PI_F * r2)); /* the cosines times r^2 */
        float plain = k * (v->flux[0] + v->flux[1] + v->flux[2]), f = 1.0f;
        if (l->view) {
            float r = sqrtf(r2), wi[3] = {d[0] / r, d[1] / r, d[2] / r};
            f = cache_specular(l->m, c->normal, l->view, wi);
        }
        float w = f * plain;
        s->all += w;
        if (visible && !visible[j])
            continue;
        s->seen += w;
        s->sw += w;
        s->plain += plain;
        for (int a = 0; a < 3; a++) {
            s->e[a] += f * k * v->flux[a];
            s->m1[a] += w * d[a];
            s->m2[a] += w * d[a] * d[a];
        }
    }
}

/* The proxy from its sums: mean position, spread, summed light. */
static void place(const light_cache *c, const proxy_sums *s, cache_proxy *out)
{
    memset(out, 0, sizeof *out);
    memcpy(out->position, c->position, sizeof out->position);
    out->visibility = s->all > 0.0f ? s->seen / s->all : 1.0f;
    if (!(s->sw > 0.0f))
        return;
    float spread = 0;
    for (int a = 0; a < 3; a++) {
        float mean = s->m1[a] / s->sw;
        out->position[a] += mean;
        float var = s->m2[a] / s->sw - mean * mean;
        spread = fmaxf(spread, var > 0.0f ? var : 0.0f);
        out->irradiance[a] = s->e[a];
    }
    out->radius = 2.0f * sqrtf(spread);
}

void cache_proxy_gather(const light_cache *c, const vpl *vals, size_t n,
                        const uint8_t *visible, cache_proxy *out)
{
    proxy_sums s;
    gather(c, vals, n, visible, &(lobe){NULL, 0}, &s);
    place(c, &s, out);
}

float cache_specular_exponent(float roughness)
{
    float alpha = roughness * roughness;
    return 2.0f / fmaxf(alpha * alpha, 1e-3f) - 2.0f;
}

float cache_specular(float m, const float n[3], const float wo[3], const float wi[3])
{
    float h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
    if (vec3_normalize(h) == 0)
        return 0.0f;
    float cos_h = vec3_dot(n, h);
    return (m + 8.0f) / (8.0f * PI_F) * CACHE_SPECULAR_F0 * powf(cos_h > 0.0f ? cos_h : 0.0f, m);
}

/* Unit direction from a to b; fallback when they meet. */
static void towards(const float a[3], const float b[3], const float fallback[3], float out[3])
{
    vec3_sub(b, a, out);
    if (vec3_normalize(out) == 0)
        memcpy(out, fallback, 3 * sizeof *out);
}

void cache_glossy_gather(const light_cache *c, const float eye[3], const vpl *vals, size_t n,
                         const uint8_t *visible, cache_proxy *out)
{
    float view[3], wp[3];
    towards(c->position, eye, c->normal, view);
    lobe l = {view, cache_specular_exponent(c->roughness)};
    proxy_sums s;
    gather(c, vals, n, visible, &l, &s);
    place(c, &s, out);
    if (!(s.sw > 0.0f))
        return;
    towards(c->position, out->position, c->normal, wp);
    float scale = 1.0f / fmaxf(cache_specular(l.m, c->normal, view, wp), s.sw / s.plain);
    for (int a = 0; a < 3; a++)
        out->irradiance[a] *= scale;
}

/* Overlap area of two axis-aligned squares (centres a, b; sides sa, sb). */
static float overlap(const float a[2], float sa, const float b[2], float sb)
{
    float o = 1.0f;
    for (int k = 0; k < 2; k++) {
        float lo = fmaxf(a[k] - 0.5f * sa, b[k] - 0.5f * sb);
        float hi = fminf(a[k] + 0.5f * sa, b[k] + 0.5f * sb);
        o *= hi > lo ? hi - lo : 0.0f;
    }
    return o;
}

float cache_occlusion(const light_cache *caches, size_t count, size_t self,
                      const cache_proxy *p)
{
    const light_cache *c = &caches[self];
    float v[3];
    vec3_sub(p->position, c->position, v);
    float d = vec3_length(v);
    if (!(d > 0.0f))
        return 1.0f;
    float w[3] = {v[0] / d, v[1] / d, v[2] / d}, cos_p = vec3_dot(c->normal, w);
    if (!(cos_p > 0.0f))
        return 1.0f;
    float t1[3], t2[3];
    vec3_basis(c->normal, t1, t2);
    float radius = fminf(p->radius, 0.9f * d), s = radius / d;
    float square_p = 2.0f * PI_F * (1.0f - sqrtf(1.0f - s * s)) * cos_p;
    if (!(square_p > 0.0f))
        return 1.0f;
    float cp[2] = {vec3_dot(w, t1), vec3_dot(w, t2)}, side_p = sqrtf(square_p);
    float blocked = 0.0f, nearer = d - radius;
    for (size_t k = 0; k < count; k++) {
        if (k == self)
            continue;
        float u[3];
        vec3_sub(caches[k].position, c->position, u);
        float r2 = vec3_dot(u, u);
        if (!(r2 > 0.0f) || r2 >= nearer * nearer)
            continue;
        float r = sqrtf(r2), wk[3] = {u[0] / r, u[1] / r, u[2] / r};
        float cos_k = vec3_dot(c->normal, wk);
        if (!(cos_k > 0.0f))
            continue;
        float solid = fminf(2.0f * PI_F, caches[k].area * fabsf(vec3_dot(caches[k].normal, wk)) / r2);
        float ck[2] = {vec3_dot(wk, t1), vec3_dot(wk, t2)};
        blocked += overlap(cp, side_p, ck, sqrtf(solid * cos_k));
    }
    return fmaxf(0.0f, 1.0f - blocked / square_p);
}

void cache_proxy_at(const light_cache *c, const cache_proxy *p, const float x[3],
                    const float n[3], float out[3])
{
    float lc[3], lx[3];
    vec3_sub(p->position, c->position, lc);
    vec3_sub(p->position, x, lx);
    float dc2 = vec3_dot(lc, lc), dx2 = vec3_dot(lx, lx), r2 = p->radius * p->radius;
    float cos_c = dc2 > 0.0f ? vec3_dot(c->normal, lc) / sqrtf(dc2) : 1.0f;
    float cos_x = dx2 > 0.0f ? vec3_dot(n, lx) / sqrtf(dx2) : 1.0f;
    float g = cos_x > 0.0f ? cos_x / fmaxf(cos_c, CACHE_PROXY_MIN_COS) * (dc2 + r2) /
                                 (dx2 + r2)
                           : 0.0f;
    if (!(dx2 + r2 > 0.0f))
        g = 1.0f; /* no proxy (no light): E is 0 anyway */
    for (int a = 0; a < 3; a++)
        out[a] = p->irradiance[a] * g;
}

/* v mirrored at unit n. */
static void reflect(const float v[3], const float n[3], float out[3])
{
    float d = 2.0f * vec3_dot(n, v);
    for (int a = 0; a < 3; a++)
        out[a] = v[a] - d * n[a];
}

/* Equation 8's glossy weight of cache c's glossy proxy p at x (normal n). */
static float glossy_weight(const light_cache *c, const cache_proxy *p, const float x[3],
                           const float n[3], float reach)
{
    float falloff = cache_falloff(c, x, n, reach);
    if (!(falloff > 0.0f))
        return 0.0f;
    float lx[3], lc[3], rx[3], rc[3];
    towards(p->position, x, n, lx);          /* incident directions: from the proxy */
    towards(p->position, c->position, c->normal, lc);
    reflect(lx, n, rx);
    reflect(lc, c->normal, rc);
    float r = vec3_dot(rx, rc);
    return r > 0.0f ? falloff * sqrtf(r) : 0.0f;
}

void cache_interpolate_glossy(const cache_grid *g, const light_cache *caches,
                              const uint8_t *hidden, const cache_proxy *glossy,
                              const float x[3], const float n[3], float roughness,
                              const float v[3], float out[3])
{
    size_t cell = cache_grid_cell(g, x);
    float sum[3] = {0, 0, 0}, pos[3] = {0, 0, 0}, weights = 0;
    for (uint32_t i = g->first[cell]; i < g->first[cell + 1]; i++) {
        uint32_t k = g->index[i];
        float w = hidden && hidden[k] ? 0.0f
                                      : glossy_weight(&caches[k], &glossy[k], x, n, g->reach);
        if (!(w > 0.0f))
            continue;
        float e[3];
        cache_proxy_at(&caches[k], &glossy[k], x, n, e);
        for (int a = 0; a < 3; a++) {
            sum[a] += w * e[a];
            pos[a] += w * glossy[k].position[a];
        }
        weights += w;
    }
    memset(out, 0, 3 * sizeof *out);
    if (!(weights > 0.0f))
        return;
    float at[3] = {pos[0] / weights, pos[1] / weights, pos[2] / weights}, l[3];
    towards(x, at, n, l);
    float f = cache_specular(cache_specular_exponent(roughness), n, v, l);
    for (int a = 0; a < 3; a++)
        out[a] = f * sum[a] / weights;
}

void cache_interpolate(const cache_grid *g, const light_cache *caches, const uint8_t *hidden,
                       const cache_proxy *proxies, const float x[3], const float n[3],
                       float out[3])
{
    size_t cell = cache_grid_cell(g, x);
    float sum[3] = {0, 0, 0}, weights = 0;
    for (uint32_t i = g->first[cell]; i < g->first[cell + 1]; i++) {
        uint32_t k = g->index[i];
        if (hidden && hidden[k])
            continue;
        float w = cache_weight(&caches[k], x, n, g->reach);
        if (!(w > 0.0f))
            continue;
        float e[3];
        cache_proxy_at(&caches[k], &proxies[k], x, n, e);
        for (int a = 0; a < 3; a++)
            sum[a] += w * e[a];
        weights += w;
    }
    for (int a = 0; a < 3; a++)
        out[a] = weights > 0.0f ? sum[a] / weights : 0.0f;
}
