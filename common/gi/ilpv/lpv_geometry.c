#include "gi/ilpv/lpv_geometry.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gi/ilpv/lpv_transfer.h"

int lpv_blockers_init(lpv_blockers *b, const int n[3])
{
    memset(b, 0, sizeof *b);
    size_t cells = 1;
    for (int a = 0; a < 3; a++) {
        if (n[a] < 1 || n[a] > (1 << 16))
            return -1;
        cells *= (size_t)n[a];
        b->n[a] = n[a];
    }
    if (cells > ((size_t)1 << 34))
        return -1;
    /* not xalloc: the lattice's size (a setting): -1 to the caller */
    b->mask = calloc(cells, sizeof *b->mask);
    if (!b->mask)
        return -1;
    b->cells = cells;
    return 0;
}

void lpv_blockers_free(lpv_blockers *b)
{
    free(b->mask);
    memset(b, 0, sizeof *b);
}

int lpv_blockers_blocked(const lpv_blockers *b, int x, int y, int z, int k)
{
    if (x < 0 || y < 0 || z < 0 || x >= b->n[0] || y >= b->n[1] || z >= b->n[2] || k < 0 ||
        k >= LPV_NEIGHBOURS)
        return 0;
    size_t i = (size_t)x + (size_t)b->n[0] * ((size_t)y + (size_t)b->n[1] * z);
    return (int)((b->mask[i] >> k) & 1u);
}

/* Does the segment p -> q cross triangle v (plane normal n)? A point on the plane counts
 * as in front; the crossing point may lie on an edge (closed meshes then leave no gap). */
static int crosses(const double v[3][3], const double n[3], const double p[3],
                   const double q[3])
{
    double dp[3], dq[3];
    vec3d_sub(p, v[0], dp);
    vec3d_sub(q, v[0], dq);
    double sp = vec3d_dot(n, dp), sq = vec3d_dot(n, dq);
    if ((sp >= 0.0) == (sq >= 0.0))
        return 0;
    double t = sp / (sp - sq), x[3];
    for (int k = 0; k < 3; k++)
        x[k] = p[k] + t * (q[k] - p[k]);
    for (int e = 0; e < 3; e++) {
        double edge[3], rel[3], c[3];
        vec3d_sub(v[(e + 1) % 3], v[e], edge);
        vec3d_sub(x, v[e], rel);
        vec3d_cross(edge, rel, c);
        if (vec3d_dot(c, n) < 0.0)
            return 0;
    }
    return 1;
}

void lpv_geometry_add_triangles(lpv_blockers *b, const lattice_desc *lat,
                                const float *positions, size_t vertex_count,
                                const unsigned *indices, size_t triangle_count,
                                lpv_geometry_stats *stats)
{
    lpv_geometry_stats st = {0};
    int usable = b && b->mask && lat && lat->n[0] == b->n[0] && lat->n[1] == b->n[1] &&
                 lat->n[2] == b->n[2] && lat->cell > 0.0f && positions;
    for (size_t t = 0; usable && t < triangle_count; t++) {
        /* Vertices in lattice units with cell centres at integer coordinates. */
        double v[3][3];
        int ok = 1;
        for (int k = 0; k < 3 && ok; k++) {
            size_t vi = indices ? indices[3 * t + k] : 3 * t + k;
            if (vi >= vertex_count) {
                ok = 0;
                break;
            }
            for (int a = 0; a < 3; a++) {
                double w = positions[3 * vi + a];
                v[k][a] = (w - lat->origin[a]) / lat->cell - 0.5;
                ok &= isfinite(v[k][a]) != 0;
            }
        }
        if (!ok) {
            st.invalid++;
            continue;
        }
        double e1[3], e2[3], n[3];
        vec3d_sub(v[1], v[0], e1);
        vec3d_sub(v[2], v[0], e2);
        vec3d_cross(e1, e2, n);
        if (!(vec3d_dot(n, n) > 0.0) || !isfinite(vec3d_dot(n, n))) {
            st.degenerate++;
            continue;
        }
        st.triangles++;
        /* Segments start at the centres in the triangle's box grown by one cell (a segment
         * spans one cell along each axis at most); the second half of the neighbours
         * (k >= 13) covers every segment once, its antipode is 25 - k. */
        int lo[3], hi[3], empty = 0;
        for (int a = 0; a < 3; a++) {
            double mn = fmin(v[0][a], fmin(v[1][a], v[2][a]));
            double mx = fmax(v[0][a], fmax(v[1][a], v[2][a]));
            lo[a] = (int)fmax(floor(mn) - 1.0, 0.0);
            hi[a] = (int)fmin(ceil(mx) + 1.0, (double)(lat->n[a] - 1));
            empty |= lo[a] > hi[a];
        }
        if (empty)
            continue;
        for (int z = lo[2]; z <= hi[2]; z++)
            for (int y = lo[1]; y <= hi[1]; y++)
                for (int x = lo[0]; x <= hi[0]; x++) {
                    double p[3] = {x, y, z};
                    size_t i = (size_t)x + (size_t)lat->n[0] * ((size_t)y + (size_t)lat->n[1] * z);
                    for (int k = LPV_NEIGHBOURS / 2; k < LPV_NEIGHBOURS; k++) {
                        const int *o = lpv_transfer_offsets[k];
                        double q[3] = {x + o[0], y + o[1], z + o[2]};
                        if (!crosses(v, n, p, q))
                            continue;
                        st.segments++;
                        b->mask[i] |= 1u << k;
                        int qx = x + o[0], qy = y + o[1], qz = z + o[2];
                        if (qx >= 0 && qy >= 0 && qz >= 0 && qx < lat->n[0] &&
                            qy < lat->n[1] && qz < lat->n[2])
                            b->mask[(size_t)qx + (size_t)lat->n[0] *
                                                     ((size_t)qy + (size_t)lat->n[1] * qz)] |=
                                1u << (LPV_NEIGHBOURS - 1 - k);
                    }
                }
    }
    if (!usable) /* nothing can be added: every triangle counts as refused input */
        st.invalid += triangle_count;
    if (stats) {
        stats->triangles += st.triangles;
        stats->degenerate += st.degenerate;
        stats->invalid += st.invalid;
        stats->segments += st.segments;
    }
}
