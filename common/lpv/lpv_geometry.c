#include "lpv/lpv_geometry.h"
#include "base/vec3.h"

#include <math.h>

#include "lpv/sh.h"

/* Sub-triangle edges are at most a quarter cell: at least about 16 samples in a fully
 * covered cell keep its total weight within some 15% of the exact coverage. The
 * subdivision per edge is capped at 2048 (a triangle that large is sampled coarser). */
enum { SAMPLES_PER_CELL_EDGE = 4, MAX_SUBDIVISION = 2048 };

/* A fully covered cell should block (about) fully: <B|Gamma_j> = 1 for light heading
 * straight into a cell-filling plane. With Gamma ~ kappa SH_cos and
 * kappa = 1 / sqrt(26 pi / 4), <SH_cos(n)|kappa SH_cos(n)> = kappa (pi/4 + pi/3). */
#define GEOMETRY_WEIGHT (1.0 / (0.22130 * (3.14159265358979 * 7.0 / 12.0)))

void lpv_geometry_add_triangles(lpv_volume *geometry, const lattice_desc *lat,
                                const float *positions, size_t vertex_count,
                                const unsigned *indices, size_t triangle_count,
                                lpv_geometry_stats *stats)
{
    lpv_geometry_stats st = {0};
    int usable = geometry && geometry->channels == LPV_GEOMETRY_CHANNELS && lat &&
                 lat->n[0] == geometry->n[0] && lat->n[1] == geometry->n[1] &&
                 lat->n[2] == geometry->n[2] && lat->cell > 0.0f && positions;
    for (size_t t = 0; usable && t < triangle_count; t++) {
        double v[3][3];
        int ok = 1;
        for (int k = 0; k < 3; k++) {
            size_t vi = indices ? indices[3 * t + k] : 3 * t + k;
            if (vi >= vertex_count) {
                ok = 0;
                break;
            }
            for (int a = 0; a < 3; a++) {
                v[k][a] = positions[3 * vi + a];
                ok &= isfinite(v[k][a]) != 0;
            }
        }
        if (!ok) {
            st.invalid++;
            continue;
        }
        double e1[3], e2[3], e3[3], cr[3];
        for (int a = 0; a < 3; a++) {
            e1[a] = v[1][a] - v[0][a];
            e2[a] = v[2][a] - v[0][a];
            e3[a] = v[2][a] - v[1][a];
        }
        vec3d_cross(e1, e2, cr);
        double twice_area = sqrt(vec3d_dot(cr, cr));
        if (!(twice_area > 0.0) || !isfinite(twice_area)) {
            st.degenerate++;
            continue;
        }
        st.triangles++;
        /* Blocking lobe around the direction into the front face (-normal): light heading
         * into a surface is stopped; closed meshes have both orientations. */
        float into[3] = {(float)-cr[0], (float)-cr[1], (float)-cr[2]}, lobe[4];
        sh_cosine_lobe(into, lobe);
        /* Regular subdivision into m^2 congruent sub-triangles with edges of at most a quarter
         * cell: every cell whose centre lies within a quarter cell of the triangle (above
         * its interior) holds the centroid of a sub-triangle, so a triangle larger than a
         * cell leaves no holes. One sample per sub-triangle, weighted by its area. */
        double longest = fmax(sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]),
                              fmax(sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]),
                                   sqrt(e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2])));
        double md = ceil(longest * SAMPLES_PER_CELL_EDGE / lat->cell);
        int m = md < 1.0 ? 1 : md > MAX_SUBDIVISION ? MAX_SUBDIVISION : (int)md;
        double cell2 = (double)lat->cell * lat->cell;
        float w = (float)(0.5 * twice_area / ((double)m * m) / cell2 * GEOMETRY_WEIGHT);
        float add[4];
        for (int s = 0; s < 4; s++)
            add[s] = w * lobe[s];
        for (int i = 0; i < m; i++) {
            for (int j = 0; j < m - i; j++) {
                /* Upward sub-triangle (i,j),(i+1,j),(i,j+1), and, where it exists, the
                 * downward one (i+1,j),(i+1,j+1),(i,j+1): centroids in barycentrics. */
                for (int down = 0; down < 2; down++) {
                    if (down && j >= m - i - 1)
                        continue;
                    double bu = down ? (i + 2.0 / 3.0) / m : (i + 1.0 / 3.0) / m;
                    double bv = down ? (j + 2.0 / 3.0) / m : (j + 1.0 / 3.0) / m;
                    float p[3];
                    for (int a = 0; a < 3; a++)
                        p[a] = (float)(v[0][a] + bu * e1[a] + bv * e2[a]);
                    size_t idx;
                    if (lattice_cell_of(lat, p, NULL, &idx) != 0) {
                        st.outside++;
                        continue;
                    }
                    for (int s = 0; s < 4; s++)
                        geometry->ch[s][idx] += add[s];
                    st.samples++;
                }
            }
        }
    }
    if (!usable) /* nothing can be injected: every triangle counts as refused input */
        st.invalid += triangle_count;
    if (stats) {
        stats->triangles += st.triangles;
        stats->degenerate += st.degenerate;
        stats->invalid += st.invalid;
        stats->samples += st.samples;
        stats->outside += st.outside;
    }
}
