/* A lit surface must not receive its own light (docs/lpv.md, "The floor"): VPLs on a disk
 * of a closed 4 x 3 x 4 m box's floor, the classic LPV (ilpv.h, classic) run until the light
 * has left (4 steps per cell of the longest axis), read by lpv_receive on a grid of points of each face,
 * against the closed form: a plane does not light itself, so the floor's one-bounce light
 * from its own VPLs is 0, and every other face gets sum_i Phi_i / pi cos_i cos / r^2 (a
 * convex room, no occlusion). At 16, 32 and 64 cells. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gi/ilpv/lattice.h"
#include "gi/ilpv/ilpv.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_inject.h"
#include "gi/ilpv/lpv_receive.h"
#include "scene/scene.h"

static const float LO[3] = {-2, 0, -2}, HI[3] = {2, 3, 2};
enum { GRID = 16 };

typedef struct disk {
    lpv_vpl *vpls;
    size_t count;
} disk;

/* A disk of radius 0.8 m at (0.6, 0, -0.6) sampled every 4 cm, flux/pi 1e-3 per VPL. */
static void make_disk(disk *d)
{
    d->vpls = malloc(10000 * sizeof *d->vpls);
    d->count = 0;
    for (float x = -0.2f; x < 1.4f; x += 0.04f)
        for (float z = -1.4f; z < 0.2f; z += 0.04f) {
            float dx = x - 0.6f, dz = z + 0.6f;
            if (dx * dx + dz * dz <= 0.64f)
                d->vpls[d->count++] = (lpv_vpl){{x, 0, z}, {0, 1, 0}, {1e-3f, 1e-3f, 1e-3f}};
        }
}

static double exact(const disk *d, const float p[3], const float n[3])
{
    double e = 0;
    for (size_t i = 0; i < d->count; i++) {
        const lpv_vpl *v = &d->vpls[i];
        double r[3] = {p[0] - v->position[0], p[1] - v->position[1], p[2] - v->position[2]};
        double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2], len = sqrt(r2);
        double c1 = (r[0] * v->normal[0] + r[1] * v->normal[1] + r[2] * v->normal[2]) / len;
        double c2 = -(r[0] * n[0] + r[1] * n[1] + r[2] * n[2]) / len;
        if (c1 > 0 && c2 > 0)
            e += v->flux[0] * c1 * c2 / r2;
    }
    return e;
}

/* Mean irradiance of face f (0..5: -x, +x, floor, ceiling, -z, +z) over a grid of points,
 * from the field and in closed form. */
static void face_means(const lpv_volume *field, const lattice_desc *lat, const disk *d, int f,
                       double *lpv, double *truth)
{
    int axis = f / 2, side = f % 2, u = (axis + 1) % 3, w = (axis + 2) % 3;
    float n[3] = {0, 0, 0};
    n[axis] = side ? -1.0f : 1.0f;
    *lpv = *truth = 0;
    for (int i = 0; i < GRID; i++)
        for (int j = 0; j < GRID; j++) {
            float p[3], rgb[3];
            p[axis] = side ? HI[axis] : LO[axis];
            p[u] = LO[u] + (HI[u] - LO[u]) * (i + 0.5f) / GRID;
            p[w] = LO[w] + (HI[w] - LO[w]) * (j + 0.5f) / GRID;
            lpv_receive_irradiance(field, lat, p, n, 1, rgb);
            *lpv += rgb[0] / (GRID * GRID);
            *truth += exact(d, p, n) / (GRID * GRID);
        }
}

static void test_the_lit_floor_does_not_light_itself(void **state)
{
    (void)state;
    disk d;
    make_disk(&d);
    scene s;
    memset(&s, 0, sizeof s);
    scene_material m = {{0.75f, 0.75f, 0.75f, 1}, -1, {0, 0, 0}, 1};
    char err[256];
    assert_int_equal(scene_add_material(&s, &m), 0);
    assert_int_equal(scene_add_box(&s, LO, HI, 1, 0), 0);
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    workpool *pool = workpool_create(2);
    const int sizes[3] = {16, 32, 64};
    for (int k = 0; k < 3; k++) {
        lattice_fit_desc fd = {.bounds_min = {LO[0], LO[1], LO[2]},
                               .bounds_max = {HI[0], HI[1], HI[2]}, .max_axis_cells = sizes[k]};
        lattice_desc lat;
        assert_int_equal(lattice_fit(&fd, &lat, err, sizeof err), 0);
        lpv_blockers b;
        ilpv c;
        assert_int_equal(lpv_blockers_init(&b, lat.n), 0);
        lpv_geometry_add_triangles(&b, &lat, s.positions, 3 * s.triangle_count, NULL,
                                   s.triangle_count, NULL);
        assert_int_equal(ilpv_init(&c, &(ilpv_desc){.lattice = &lat, .blockers = &b,
                                                    .pool = pool}), 0);
        double floor_lpv[2];
        for (int steps = 0; steps < 2; steps++) { /* the splat alone, then the whole field */
            ilpv_begin_frame(&c);
            lpv_inject_vpls(ilpv_injection(&c), ilpv_origin(&c), &lat, d.vpls, d.count, NULL);
            ilpv_frame_desc frame = {.steps = steps ? 4 * sizes[k] : 0, .classic = 1,
                                     .emitted_energy = 1.0};
            assert_int_equal(ilpv_frame(&c, &frame), 0);
            double truth;
            face_means(ilpv_result(&c), &lat, &d, 2, &floor_lpv[steps], &truth);
            assert_true(truth == 0.0);
        }
        double ceiling, ceiling_truth;
        face_means(ilpv_result(&c), &lat, &d, 3, &ceiling, &ceiling_truth);
        printf("%d cells: the floor reads %.3g of its own light after the splat, %.3g with "
               "every age (%.4f of the ceiling's closed form %.4g; the ceiling reads %.3f of it)\n",
               sizes[k], floor_lpv[0], floor_lpv[1], floor_lpv[1] / ceiling_truth, ceiling_truth,
               ceiling / ceiling_truth);
        assert_true(floor_lpv[0] == 0.0); /* nothing of the splat in the floor's own layer */
        assert_true(floor_lpv[1] < 0.04 * ceiling_truth);
        ilpv_free(&c);
        lpv_blockers_free(&b);
    }
    workpool_destroy(pool);
    scene_free(&s);
    free(d.vpls);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_lit_floor_does_not_light_itself),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
