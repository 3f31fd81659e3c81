#include "gi/caches/val_select.h"

#include "base/fnv1a.h"

#include "base/fnv1a.h"

#include <string.h>

float val_view_term(const vpl *v, const float *samples, int nsamples)
{
    const float pi = 3.14159265358979f;
    float sum = 0.0f;
    for (int s = 0; s < nsamples; s++) {
        const float *x = samples + 6 * s;
        float d[3] = {x[0] - v->position[0], x[1] - v->position[1], x[2] - v->position[2]};
        float r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (!(r2 > 0.0f))
            continue;
        float cos_l = v->normal[0] * d[0] + v->normal[1] * d[1] + v->normal[2] * d[2];
        float cos_s = -(x[3] * d[0] + x[4] * d[1] + x[5] * d[2]);
        if (cos_l > 0.0f && cos_s > 0.0f) /* the cosines times r^2 */
            sum += cos_l * cos_s / (r2 * (v->area + pi * r2));
    }
    return nsamples > 0 ? sum / (float)nsamples : 0.0f;
}

void val_importance(const vpl *v, const float *samples, int nsamples, float out[2])
{
    float phi = v->flux[0] + v->flux[1] + v->flux[2];
    if (!(phi > 0.0f)) {
        out[0] = out[1] = 0.0f;
        return;
    }
    out[0] = phi * val_view_term(v, samples, nsamples);
    out[1] = phi;
}

void val_sat_build(float *imp, int columns, int rows, float *row)
{
    for (int c = 0; c < columns; c++) {
        float *col = imp + 2 * (size_t)c * rows;
        for (int y = 1; y < rows; y++) {
            col[2 * y] += col[2 * y - 2];
            col[2 * y + 1] += col[2 * y - 1];
        }
    }
    /* The GPU's order: each chunk's columns summed in order, then the chunks' offsets. */
    int per = (columns + VAL_SAT_CHUNKS - 1) / VAL_SAT_CHUNKS;
    float chunk[VAL_SAT_CHUNKS][2];
    for (int k = 0; k < VAL_SAT_CHUNKS; k++) {
        float s[2] = {0.0f, 0.0f};
        for (int c = k * per; c < (k + 1) * per && c < columns; c++) {
            const float *total = imp + 2 * ((size_t)c * rows + rows - 1);
            s[0] += total[0];
            s[1] += total[1];
            row[2 * c] = s[0];
            row[2 * c + 1] = s[1];
        }
        chunk[k][0] = s[0];
        chunk[k][1] = s[1];
    }
    float offset[2] = {0.0f, 0.0f};
    for (int k = 0; k < VAL_SAT_CHUNKS; k++) {
        for (int c = k * per; c < (k + 1) * per && c < columns; c++) {
            row[2 * c] += offset[0];
            row[2 * c + 1] += offset[1];
        }
        offset[0] += chunk[k][0];
        offset[1] += chunk[k][1];
    }
}

/* The mixture a q_v + b q_f of a pair of sums. */
static float mix2(const float *s, float a, float b) { return a * s[0] + b * s[1]; }

/* The first of n entries (stride 2 floats) whose mixed sum exceeds t, or the last; then
 * back to one with a non-empty interval. *interval gets its interval. */
static int search(const float *s, int n, float a, float b, float t, float *interval)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (mix2(s + 2 * mid, a, b) > t)
            hi = mid;
        else
            lo = mid + 1;
    }
    for (;; lo--) {
        float below = lo > 0 ? mix2(s + 2 * (lo - 1), a, b) : 0.0f;
        *interval = mix2(s + 2 * lo, a, b) - below;
        if (*interval > 0.0f || lo == 0)
            return lo;
    }
}

int val_sat_select(const float *sums, const float *row, int columns, int rows, int n,
                   uint32_t seed, val_pick *out)
{
    const float *last = row + 2 * (columns - 1);
    if (!(last[1] > 0.0f) || n <= 0)
        return 0;
    float a = last[0] > 0.0f ? 0.5f / last[0] : 0.0f, b = 0.5f / last[1];
    float total = mix2(last, a, b);
    for (int i = 0; i < n; i++) {
        float u = (float)vpl_slot_random(seed, i, 0);
        float target = total * (((float)i + u) / (float)n), column_width, width;
        int c = search(row, columns, a, b, target, &column_width);
        float base = c > 0 ? mix2(row + 2 * (c - 1), a, b) : 0.0f;
        int y = search(sums + 2 * (size_t)c * rows, rows, a, b, target - base, &width);
        out[i] = (val_pick){c, y, width > 0.0f ? total / ((float)n * width) : 0.0f};
    }
    return n;
}

uint64_t val_hash_words(uint64_t h, const void *words, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        uint32_t w;
        memcpy(&w, (const char *)words + 4 * i, sizeof w);
        h = fnv1a64_le(h, w, 4);
    }
    return h;
}

uint64_t val_pick_checksum(const val_pick *p, int n, uint64_t h)
{
    for (int i = 0; i < n; i++) {
        uint32_t w[3] = {(uint32_t)p[i].column, (uint32_t)p[i].row, 0};
        memcpy(&w[2], &p[i].weight, sizeof w[2]);
        h = val_hash_words(h, w, 3);
    }
    return h;
}
