#include "caches/cache_light.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

static const float PI_F = 3.14159265358979f;

void cache_proxy_gather(const light_cache *c, const vpl *vals, size_t n,
                        const uint8_t *visible, cache_proxy *out)
{
    float e[3] = {0, 0, 0}, sw = 0, m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0}, seen = 0, all = 0;
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
        float w = k * (v->flux[0] + v->flux[1] + v->flux[2]);
        all += w;
        if (visible && !visible[j])
            continue;
        seen += w;
        sw += w;
        for (int a = 0; a < 3; a++) {
            e[a] += k * v->flux[a];
            m1[a] += w * d[a];
            m2[a] += w * d[a] * d[a];
        }
    }
    memset(out, 0, sizeof *out);
    memcpy(out->position, c->position, sizeof out->position);
    out->visibility = all > 0.0f ? seen / all : 1.0f;
    if (!(sw > 0.0f))
        return;
    float spread = 0;
    for (int a = 0; a < 3; a++) {
        float mean = m1[a] / sw;
        out->position[a] += mean;
        float var = m2[a] / sw - mean * mean;
        spread = fmaxf(spread, var > 0.0f ? var : 0.0f);
        out->irradiance[a] = e[a];
    }
    out->radius = 2.0f * sqrtf(spread);
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
