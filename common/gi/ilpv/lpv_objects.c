/* lpv_objects: blockers that follow moving objects, redone only around them
 * (lpv_objects.h). */
#include "gi/ilpv/lpv_objects.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"

enum { REACH = 1 }; /* a segment crossing a triangle has both ends within one cell of its box */ /* cells around a triangle's box its bits may touch */

static size_t cell_index(const lattice_desc *lat, int x, int y, int z)
{
    return (size_t)x + (size_t)lat->n[0] * ((size_t)y + (size_t)lat->n[1] * z);
}

/* Object k's triangles through model (NULL: as loaded) into o->moved_positions, and the
 * cells they may touch into box; returns the vertex count. */
static size_t place(lpv_objects *o, const lattice_desc *lat, const scene *s, int k, const float *model,
                    int box[6])
{
    size_t n = 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = o->first[k]; i < o->first[k + 1]; i++)
        for (int v = 0; v < 3; v++, n++) {
            float *p = o->moved_positions + 3 * n;
            const float *src = s->positions + 9 * o->tri[i] + 3 * v;
            if (model)
                mat4_transform_point(model, src, p);
            else
                memcpy(p, src, 3 * sizeof(float));
            for (int a = 0; a < 3; a++) {
                double c = (p[a] - lat->origin[a]) / lat->cell - 0.5;
                lo[a] = fmin(lo[a], c);
                hi[a] = fmax(hi[a], c);
            }
        }
    for (int a = 0; a < 3; a++) {
        /* Non-finite or far outside: the box is clipped, lpv_geometry skips what is out. */
        double l = isfinite(lo[a]) ? floor(lo[a]) - REACH : 0, h = isfinite(hi[a]) ? ceil(hi[a]) + REACH : -1;
        box[a] = (int)fmax(l, 0.0);
        box[3 + a] = (int)fmin(h, (double)(lat->n[a] - 1));
        if (!(l <= h)) {
            box[a] = 1;
            box[3 + a] = 0;
        }
    }
    return n;
}

static int box_empty(const int box[6])
{
    return box[0] > box[3] || box[1] > box[4] || box[2] > box[5];
}

int lpv_objects_init(lpv_objects *o, lpv_blockers *b, const lattice_desc *lat, const scene *s)
{
    memset(o, 0, sizeof *o);
    o->count = s->object_count;
    size_t nt = s->triangle_count, cells = lattice_cell_count(lat);
    /* not xalloc: the scene's objects and triangles, the lattice's cells: -1 to the caller */
    o->first = calloc((size_t)o->count + 2, sizeof *o->first);
    o->tri = malloc((nt ? nt : 1) * sizeof *o->tri);
    o->dirty = calloc(cells, 1);
    if (!o->first || !o->tri || !o->dirty || lpv_blockers_init(&o->fixed, lat->n) != 0) {
        lpv_objects_free(o);
        return -1;
    }
    /* Counting sort by object, the static triangles (-1) in slot count. */
    for (size_t t = 0; t < nt; t++) {
        int k = s->triangle_object ? s->triangle_object[t] : -1;
        o->first[(k < 0 ? o->count : k) + 1]++;
    }
    size_t largest = 1;
    for (int k = 0; k <= o->count; k++) {
        largest = o->first[k + 1] > largest ? o->first[k + 1] : largest;
        o->first[k + 1] += o->first[k];
    }
    /* not xalloc: the scene's largest object: -1 to the caller */
    o->moved_positions = malloc(largest * 9 * sizeof(float));
    size_t *fill = calloc((size_t)o->count + 1, sizeof *fill);
    if (!fill || !o->moved_positions) {
        free(fill);
        lpv_objects_free(o);
        return -1;
    }
    for (size_t t = 0; t < nt; t++) {
        int k = s->triangle_object ? s->triangle_object[t] : -1;
        k = k < 0 ? o->count : k;
        o->tri[o->first[k] + fill[k]++] = t;
    }
    free(fill);
    int box[6];
    size_t n = place(o, lat, s, o->count, NULL, box); /* the static triangles */
    lpv_geometry_add_triangles(&o->fixed, lat, o->moved_positions, n, NULL, n / 3, NULL);
    memcpy(b->mask, o->fixed.mask, cells * sizeof *b->mask);
    for (int k = 0; k < o->count; k++) {
        n = place(o, lat, s, k, NULL, o->box[k]);
        lpv_geometry_add_triangles(b, lat, o->moved_positions, n, NULL, n / 3, NULL);
    }
    return 0;
}

void lpv_objects_free(lpv_objects *o)
{
    lpv_blockers_free(&o->fixed);
    free(o->first);
    free(o->tri);
    free(o->moved_positions);
    free(o->dirty);
    memset(o, 0, sizeof *o);
}

/* Marks box's cells dirty and puts the static bits back there; returns how many were new. */
static size_t redo_cells(lpv_objects *o, lpv_blockers *b, const lattice_desc *lat, const int box[6])
{
    size_t count = 0;
    for (int z = box[2]; z <= box[5]; z++)
        for (int y = box[1]; y <= box[4]; y++)
            for (int x = box[0]; x <= box[3]; x++) {
                size_t i = cell_index(lat, x, y, z);
                if (o->dirty[i])
                    continue;
                o->dirty[i] = 1;
                b->mask[i] = o->fixed.mask[i];
                count++;
            }
    return count;
}

static int touches_dirty(const lpv_objects *o, const lattice_desc *lat, const int box[6])
{
    for (int z = box[2]; z <= box[5]; z++)
        for (int y = box[1]; y <= box[4]; y++)
            for (int x = box[0]; x <= box[3]; x++)
                if (o->dirty[cell_index(lat, x, y, z)])
                    return 1;
    return 0;
}

static void clear_dirty(lpv_objects *o, const lattice_desc *lat, const int box[6])
{
    for (int z = box[2]; z <= box[5]; z++)
        for (int y = box[1]; y <= box[4]; y++)
            memset(o->dirty + cell_index(lat, box[0], y, z), 0, (size_t)(box[3] - box[0] + 1));
}

void lpv_objects_update(lpv_objects *o, lpv_blockers *b, const lattice_desc *lat, const scene *s,
                        const float (*model)[16], const uint8_t *shown, const uint8_t *moved,
                        lpv_objects_stats *stats)
{
    lpv_objects_stats st = {0};
    int old_box[SCENE_MAX_OBJECTS][6];
    memcpy(old_box, o->box, sizeof old_box);
    /* 1. The cells the moved objects leave and enter get the static bits back. */
    for (int k = 0; k < o->count; k++) {
        if (!moved[k])
            continue;
        st.objects_moved++;
        if (shown[k])
            place(o, lat, s, k, model[k], o->box[k]);
        else
            o->box[k][0] = 1, o->box[k][3] = 0;
        if (!box_empty(old_box[k]))
            st.cells_redone += redo_cells(o, b, lat, old_box[k]);
        if (!box_empty(o->box[k]))
            st.cells_redone += redo_cells(o, b, lat, o->box[k]);
    }
    /* 2. Every shown object near those cells adds its triangles again (bits it sets
     * elsewhere are set already: OR). */
    for (int k = 0; k < o->count && st.cells_redone; k++) {
        if (!shown[k] || box_empty(o->box[k]) || !touches_dirty(o, lat, o->box[k]))
            continue;
        int box[6];
        size_t n = place(o, lat, s, k, model[k], box);
        lpv_geometry_add_triangles(b, lat, o->moved_positions, n, NULL, n / 3, NULL);
        st.triangles_added += n / 3;
    }
    for (int k = 0; k < o->count; k++)
        if (moved[k]) {
            if (!box_empty(old_box[k]))
                clear_dirty(o, lat, old_box[k]);
            if (!box_empty(o->box[k]))
                clear_dirty(o, lat, o->box[k]);
        }
    if (stats)
        *stats = st;
}
