/* common/caches: the light caches of the caches GI method without GL.
 *   placement: the caches' density follows the setting, their areas add up to the scene's,
 *     every surface point (sampled apart from the placement's own points) is within reach
 *     of a cache that faces its way, on the built-in scenes too, and the same scene gives
 *     the same caches bit for bit;
 *   the disk cache: a file written is read back whole; a truncated, damaged (one byte
 *     flipped), stale (another format version or setting) or foreign file is refused and
 *     the caches placed again and rewritten; a folder that cannot be created or a file that
 *     cannot be written only costs the placement;
 *   selection: the summed-area tables and binary search pick each texel as often as its
 *     probability says (|count - n p| <= 2 under stratification) with weight 1 / (n p),
 *     like vpl_select()'s brute-force linear sampler of the same mixture;
 *   1/P: a cache's irradiance from importance-sampled VALs of a uniform emitter square is
 *     on average its closed form (and the sum over every VAL) within its statistical bound;
 *   occlusion: a wall of caches between a cache and its proxy blocks it, nothing between
 *     blocks nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gi/caches/cache_file.h"
#include "gi/caches/cache_grid.h"
#include "gi/caches/cache_light.h"
#include "gi/caches/cache_place.h"
#include "gi/caches/val_select.h"
#include "gi/vpl/vpl_select.h"

/* A closed 4 x 3 x 4 m room facing in, a box on its floor, a slanted panel. */
static void room(scene *s)
{
    memset(s, 0, sizeof *s);
    scene_material m = {{0.8f, 0.8f, 0.8f, 1}, -1, {0, 0, 0}, 1};
    assert_true(scene_add_material(s, &m) >= 0);
    const float lo[3] = {-2, 0, -2}, hi[3] = {2, 3, 2}, b0[3] = {-0.5f, 0, -0.5f},
                b1[3] = {0.3f, 0.7f, 0.4f};
    assert_int_equal(scene_add_box(s, lo, hi, 1, 0), 0);
    assert_int_equal(scene_add_box(s, b0, b1, 0, 0), 0);
    const float a[3] = {1, 0.5f, 1}, b[3] = {1.8f, 0.5f, 1}, c[3] = {1.8f, 1.5f, 1.6f},
                d[3] = {1, 1.5f, 1.6f}, n[3] = {0, -0.514496f, 0.857493f};
    assert_int_equal(scene_add_quad(s, a, b, c, d, n, 0), 0);
    char err[128];
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
}

static void place(const scene *s, float density, cache_set *out)
{
    char err[256];
    cache_place_desc d = {cache_place_edge(s, density), 30.0f * 3.14159265f / 180.0f};
    if (cache_place(s, &d, out, err, sizeof err) != 0)
        fail_msg("%s", err);
}

static void test_density_and_area(void **state)
{
    (void)state;
    scene s;
    room(&s);
    double area = cache_scene_area(&s);
    for (float density = 1; density <= 16; density *= 4) {
        cache_set set;
        place(&s, density, &set);
        double sum = 0;
        for (size_t i = 0; i < set.count; i++)
            sum += set.caches[i].area;
        print_message("density %g/m^2: %zu caches on %.1f m^2 (%.2f per m^2)\n", density,
                      set.count, area, set.count / area);
        assert_true(fabs(sum - area) < 1e-3 * area);
        /* a face of a x b m makes about (a / e + 1) (b / e + 1) caches: its edges cut
         * cubes; the room's shortest side is 3 m */
        double e = 1 / sqrt(density), most = density * area * 1.1 * (1 + e / 3) * (1 + e / 3);
        assert_true(set.count >= 0.9 * density * area && set.count <= most);
        cache_set_free(&set);
    }
    scene_free(&s);
}

/* Every surface point has weight > 0 from some cache. */
static void check_reach(const scene *s, const cache_set *set, const char *what)
{
    cache_grid g;
    char err[128];
    assert_int_equal(cache_grid_build(set, s->bounds_min, s->bounds_max, &g, err, sizeof err), 0);
    size_t n = cache_surface_points(s, 0.37f * set->edge, NULL);
    float *pts = malloc(n * CACHE_POINT_FLOATS * sizeof *pts);
    cache_surface_points(s, 0.37f * set->edge, pts);
    size_t missed = 0;
    double least = INFINITY;
    for (size_t i = 0; i < n; i++) {
        const float *x = pts + CACHE_POINT_FLOATS * i;
        size_t cell = cache_grid_cell(&g, x);
        double w = 0;
        for (uint32_t k = g.first[cell]; k < g.first[cell + 1]; k++)
            w += cache_weight(&set->caches[g.index[k]], x, x + 3, g.reach);
        missed += !(w > 0);
        least = fmin(least, w);
    }
    print_message("%s: %zu caches, %zu points, %zu unreached, least weight sum %.3f, longest "
                  "list %d\n", what, set->count, n, missed, least, g.longest);
    assert_int_equal(missed, 0);
    assert_true(g.longest <= CACHE_GRID_MAX_LIST);
    free(pts);
    cache_grid_free(&g);
}

static void test_every_point_reached(void **state)
{
    (void)state;
    scene s;
    room(&s);
    for (float density = 2; density <= 32; density *= 4) {
        cache_set set;
        place(&s, density, &set);
        check_reach(&s, &set, "room");
        cache_set_free(&set);
    }
    scene_free(&s);
    const char *builtin[] = {"default", "corridor", "doorway", "courtyard"};
    for (int i = 0; i < 4; i++) {
        char err[256];
        assert_int_equal(scene_load(builtin[i], &s, err, sizeof err), 0);
        cache_set set;
        place(&s, 0, &set);
        check_reach(&s, &set, builtin[i]);
        cache_set_free(&set);
        scene_free(&s);
    }
}

static void test_deterministic(void **state)
{
    (void)state;
    scene s;
    room(&s);
    cache_set a, b;
    place(&s, 4, &a);
    place(&s, 4, &b);
    assert_int_equal(a.count, b.count);
    assert_memory_equal(a.caches, b.caches, a.count * sizeof *a.caches);
    cache_set_free(&a);
    cache_set_free(&b);
    scene_free(&s);
}

/* ---- the disk cache ------------------------------------------------------------------ */

static char dir[200];

static int setup_dir(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "%s/test_caches_files.%ld", CAVELIGHT_BINARY_DIR, (long)getpid());
    return 0;
}

static int teardown_dir(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "chmod -R u+w '%s' 2>/dev/null; rm -rf '%s'", dir, dir);
    return system(cmd) == 0 ? 0 : -1;
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* cache_store_get() into a fresh set: from the file? and its note. */
static int get(const scene *s, const cache_place_desc *d, const char *where, cache_set *out,
               cache_store_report *rep)
{
    char err[256];
    assert_int_equal(cache_store_get(s, d, where, out, rep, err, sizeof err), 0);
    if (rep->note[0])
        print_message("note: %s\n", rep->note);
    return rep->from_file;
}

static void damage(const char *path, long at, int truncate_to)
{
    if (truncate_to) {
        assert_int_equal(truncate(path, at), 0);
        return;
    }
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    fseek(f, at, SEEK_SET);
    int c = fgetc(f);
    fseek(f, at, SEEK_SET);
    fputc(c ^ 0x10, f);
    fclose(f);
}

static void test_file_cases(void **state)
{
    (void)state;
    scene s;
    room(&s);
    cache_place_desc d = {cache_place_edge(&s, 4), 0.5f};
    cache_set placed, got;
    cache_store_report rep;
    assert_int_equal(get(&s, &d, dir, &placed, &rep), 0); /* absent: placed, written */
    assert_string_equal(rep.note, "");
    long size = file_size(rep.path);
    assert_int_equal(size, 40 + 4 * CACHE_RECORD_FLOATS * (long)placed.count + 8);
    assert_int_equal(get(&s, &d, dir, &got, &rep), 1);   /* read back whole */
    assert_int_equal(got.count, placed.count);
    assert_memory_equal(got.caches, placed.caches, got.count * sizeof *got.caches);
    cache_set_free(&got);
    /* truncated, one byte flipped in a record, in the trailer, in the header's count */
    const long cut[4][2] = {{size - 5, 1}, {40 + 4 * CACHE_RECORD_FLOATS * 3 + 2, 0}, {size - 3, 0}, {33, 0}};
    for (int k = 0; k < 4; k++) {
        damage(rep.path, cut[k][0], (int)cut[k][1]);
        assert_int_equal(get(&s, &d, dir, &got, &rep), 0);
        assert_non_null(strstr(rep.note, "placed again"));
        assert_memory_equal(got.caches, placed.caches, got.count * sizeof *got.caches);
        cache_set_free(&got);
        assert_int_equal(file_size(rep.path), size); /* rewritten */
        assert_int_equal(get(&s, &d, dir, &got, &rep), 1);
        cache_set_free(&got);
    }
    /* stale: the file of these settings holds another version's or setting's key */
    cache_key key = cache_key_of(&s, &d), other = key;
    char why[256], path[600];
    cache_file_path(dir, &key, path, sizeof path);
    for (int k = 0; k < 2; k++) {
        if (k == 0)
            other.version = key.version + 1;
        else
            other = key, other.angle = key.angle * 0.5f;
        assert_int_equal(cache_file_write(path, &other, &placed, why, sizeof why), 0);
        assert_int_equal(cache_file_read(path, &key, &got, why, sizeof why), -1);
        assert_non_null(strstr(why, "another"));
        assert_int_equal(get(&s, &d, dir, &got, &rep), 0);
        cache_set_free(&got);
    }
    /* another scene's name never meets it */
    scene moved;
    room(&moved);
    moved.positions[0] += 0.25f;
    cache_key mk = cache_key_of(&moved, &d);
    char mpath[600];
    cache_file_path(dir, &mk, mpath, sizeof mpath);
    assert_string_not_equal(mpath, path);
    scene_free(&moved);
    cache_set_free(&placed);
    scene_free(&s);
}

static void test_unwritable(void **state)
{
    (void)state;
    scene s;
    room(&s);
    cache_place_desc d = {cache_place_edge(&s, 4), 0.5f};
    cache_set set;
    cache_store_report rep;
    char sub[400], blocker[400];
    /* a folder that cannot be made: a file stands where it would be */
    snprintf(blocker, sizeof blocker, "%s/blocker", dir);
    snprintf(sub, sizeof sub, "%s/blocker/caches", dir);
    assert_int_equal(get(&s, &d, dir, &set, &rep), 0);
    cache_set_free(&set);
    FILE *f = fopen(blocker, "w");
    assert_non_null(f);
    fclose(f);
    for (int k = 0; k < 2; k++) {
        assert_int_equal(get(&s, &d, sub, &set, &rep), 0);
        assert_true(set.count > 0);
        assert_non_null(strstr(rep.note, "not stored"));
        cache_set_free(&set);
    }
    /* a file that cannot be written: its name is taken by a folder */
    char taken[600];
    cache_key key = cache_key_of(&s, &d);
    snprintf(sub, sizeof sub, "%s/taken", dir);
    cache_file_path(sub, &key, taken, sizeof taken);
    assert_int_equal(mkdir(sub, 0755), 0);
    assert_int_equal(mkdir(taken, 0755), 0);
    assert_int_equal(get(&s, &d, sub, &set, &rep), 0);
    assert_true(set.count > 0);
    assert_non_null(strstr(rep.note, "not stored"));
    cache_set_free(&set);
    /* a read-only folder (not for root, who may write anyway) */
    if (geteuid() != 0) {
        snprintf(sub, sizeof sub, "%s/readonly", dir);
        assert_int_equal(mkdir(sub, 0555), 0);
        assert_int_equal(get(&s, &d, sub, &set, &rep), 0);
        assert_non_null(strstr(rep.note, "not stored"));
        cache_set_free(&set);
    }
    /* no folder at all: placed every time, quietly */
    assert_int_equal(get(&s, &d, NULL, &set, &rep), 0);
    assert_string_equal(rep.note, "");
    cache_set_free(&set);
    scene_free(&s);
}

/* ---- selection ----------------------------------------------------------------------- */

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

enum { COLUMNS = 24, ROWS = 16, TEXELS = COLUMNS * ROWS, SLOTS = 4096 };

/* Importance pairs (view, flux) for the texels, column-major; some unlit, some unseen. */
static void importance(float *imp)
{
    uint32_t s = 11;
    for (int j = 0; j < TEXELS; j++) {
        float f = j % 7 == 2 ? 0.0f : (float)(1 + lcg(&s) % 100);
        float v = j % 5 == 1 ? 0.0f : (float)(lcg(&s) % 1000) / 1000.0f;
        imp[2 * j] = f * v;
        imp[2 * j + 1] = f;
    }
}

static void test_sat_against_brute_force(void **state)
{
    (void)state;
    static float imp[2 * TEXELS], sums[2 * TEXELS], row[2 * COLUMNS];
    static val_pick picks[SLOTS];
    importance(imp);
    memcpy(sums, imp, sizeof imp);
    val_sat_build(sums, COLUMNS, ROWS, row);
    assert_int_equal(val_sat_select(sums, row, COLUMNS, ROWS, SLOTS, 5, picks), SLOTS);
    double qv = 0, qf = 0;
    for (int j = 0; j < TEXELS; j++)
        qv += imp[2 * j], qf += imp[2 * j + 1];
    /* The brute force: vpl_select()'s view rule on the same mixture (flux f, view term v). */
    static vpl cand[TEXELS];
    static double view[TEXELS], cdf[TEXELS];
    static vpl chosen[SLOTS];
    static size_t which[SLOTS];
    for (int j = 0; j < TEXELS; j++) {
        memset(&cand[j], 0, sizeof cand[j]);
        cand[j].flux[0] = imp[2 * j + 1];
        view[j] = imp[2 * j + 1] > 0 ? imp[2 * j] / imp[2 * j + 1] : 0;
    }
    vpl_select_desc bd = {.candidates = cand, .count = TEXELS, .texels = TEXELS,
                          .rule = VPL_SELECT_VIEW, .view = view, .n = SLOTS, .seed = 5};
    assert_int_equal(vpl_select(&bd, cdf, chosen, which), SLOTS);
    static int count[TEXELS], brute[TEXELS];
    for (int i = 0; i < SLOTS; i++) {
        int j = picks[i].column * ROWS + picks[i].row;
        count[j]++;
        brute[which[i]]++;
        double p = 0.5 * (imp[2 * j] / qv + imp[2 * j + 1] / qf);
        assert_true(p > 0);
        double expect = 1.0 / (SLOTS * p);
        if (fabs(picks[i].weight - expect) > 1e-3 * expect)
            fail_msg("slot %d: texel %d weight %g, 1/(n p) %g", i, j, picks[i].weight, expect);
    }
    double worst = 0, worst_brute = 0;
    for (int j = 0; j < TEXELS; j++) {
        double np = SLOTS * 0.5 * (imp[2 * j] / qv + imp[2 * j + 1] / qf);
        worst = fmax(worst, fabs(count[j] - np));
        worst_brute = fmax(worst_brute, fabs(brute[j] - np));
        if (imp[2 * j + 1] == 0)
            assert_int_equal(count[j], 0);
    }
    print_message("largest |count - n p|: SAT %.3f, brute-force sampler %.3f\n", worst,
                  worst_brute);
    assert_true(worst <= 2.0);
    assert_true(worst_brute <= 2.0);
}

/* ---- 1/P ----------------------------------------------------------------------------- */

static const double PI = 3.14159265358979323846;

/* The irradiance straight below a Lambertian square of side a and radiance L at height h,
 * facing down: four corner rectangles' form factors (the closed form). */
static double square_irradiance(double L, double a, double h)
{
    double x = 0.5 * a / h, y = x;
    double f = (x / sqrt(1 + x * x) * atan(y / sqrt(1 + x * x)) +
                y / sqrt(1 + y * y) * atan(x / sqrt(1 + y * y))) / (2 * PI);
    return 4 * PI * L * f;
}

static void test_unbiased_on_emitter_square(void **state)
{
    (void)state;
    enum { SIDE = 48, N = 256, SEEDS = 400 };
    const double a = 2.0, h = 1.0, L = 3.0;
    static vpl texel[SIDE * SIDE], picked[N];
    static float imp[2 * SIDE * SIDE], row[2 * SIDE];
    static val_pick picks[N];
    /* view samples off to one side, so the importance is far from uniform */
    const float samples[2 * 6] = {1.5f, 0.2f, 0.4f, 0, 1, 0, 0.8f, 0.3f, -1.0f, 0, 1, 0};
    for (int x = 0; x < SIDE; x++)
        for (int y = 0; y < SIDE; y++) {
            vpl *v = &texel[x * SIDE + y]; /* column x, row y */
            float area = (float)(a * a / (SIDE * SIDE));
            *v = (vpl){{(float)(-a / 2 + a * (x + 0.5) / SIDE), (float)h,
                        (float)(-a / 2 + a * (y + 0.5) / SIDE)}, {0, -1, 0},
                       {(float)(PI * L * area), (float)(PI * L * area) * 0.5f, 0}, area};
            val_importance(v, samples, 2, imp + 2 * (x * SIDE + y));
        }
    val_sat_build(imp, SIDE, SIDE, row);
    light_cache c = {{0, 0, 0}, {0, 1, 0}, 0.01f, 1};
    cache_proxy all;
    cache_proxy_gather(&c, texel, SIDE * SIDE, NULL, &all);
    double sum = 0, sum2 = 0;
    for (int seed = 0; seed < SEEDS; seed++) {
        assert_int_equal(val_sat_select(imp, row, SIDE, SIDE, N, (uint32_t)seed, picks), N);
        for (int i = 0; i < N; i++) {
            picked[i] = texel[picks[i].column * SIDE + picks[i].row];
            for (int k = 0; k < 3; k++) /* the area stays the texel's (caches_select.comp) */
                picked[i].flux[k] *= picks[i].weight;
        }
        cache_proxy p;
        cache_proxy_gather(&c, picked, N, NULL, &p);
        sum += p.irradiance[0];
        sum2 += (double)p.irradiance[0] * p.irradiance[0];
    }
    double mean = sum / SEEDS, se = sqrt(fmax(sum2 / SEEDS - mean * mean, 0) / SEEDS);
    double exact = square_irradiance(L, a, h);
    print_message("irradiance below the square: closed form %.5f, every VAL %.5f, "
                  "importance-sampled mean %.5f +- %.5f (%d seeds of %d VALs)\n", exact,
                  all.irradiance[0], mean, se, SEEDS, N);
    assert_true(fabs(all.irradiance[0] - exact) < 0.01 * exact); /* the disk bound's bias */
    assert_true(fabs(mean - all.irradiance[0]) < 4 * se + 1e-4 * exact);
    assert_true(se < 0.01 * exact);
}

/* ---- glossy proxies ------------------------------------------------------------------ */

/* The glossy proxy (equation 7) reproduces its VALs where the lobe cannot tell them apart:
 * at roughness 1 (a constant lobe) it is the diffuse proxy, and of one VAL it is that VAL's
 * irradiance at any roughness. On a smooth cache it moves to the VAL in the mirror
 * direction of the viewer, where the diffuse proxy lies between the two. */
static void test_glossy_proxy(void **state)
{
    (void)state;
    const vpl vals[2] = {{{1, 1, 0}, {-0.7071f, -0.7071f, 0}, {1, 1, 1}, 0.01f},
                         {{-1, 1, 0}, {0.7071f, -0.7071f, 0}, {1, 1, 1}, 0.01f}};
    const float eye[3] = {-3, 3, 0}; /* mirrors onto vals[0] */
    light_cache c = {{0, 0, 0}, {0, 1, 0}, 0.01f, 1};
    cache_proxy d, g;
    cache_proxy_gather(&c, vals, 2, NULL, &d);
    cache_glossy_gather(&c, eye, vals, 2, NULL, &g);
    for (int k = 0; k < 3; k++) {
        assert_float_equal(g.position[k], d.position[k], 1e-5);
        assert_float_equal(g.irradiance[k], d.irradiance[k], 1e-5 * d.irradiance[k]);
    }
    c.roughness = 0.3f;
    for (int j = 0; j < 2; j++) {
        cache_proxy_gather(&c, vals + j, 1, NULL, &d);
        cache_glossy_gather(&c, eye, vals + j, 1, NULL, &g);
        assert_float_equal(g.irradiance[0], d.irradiance[0], 1e-5 * d.irradiance[0]);
    }
    cache_proxy_gather(&c, vals, 2, NULL, &d);
    cache_glossy_gather(&c, eye, vals, 2, NULL, &g);
    print_message("smooth cache: diffuse proxy at x %.3f, glossy at x %.3f (the mirrored VAL "
                  "at 1)\n", d.position[0], g.position[0]);
    assert_float_equal(d.position[0], 0, 1e-5);
    assert_true(g.position[0] > 0.99f);
}

/* ---- occlusion ----------------------------------------------------------------------- */

static void test_occlusion_by_a_wall(void **state)
{
    (void)state;
    enum { SIDE = 21 };
    static light_cache caches[1 + SIDE * SIDE];
    caches[0] = (light_cache){{0, 0, 0}, {0, 1, 0}, 0.04f, 1};
    /* a horizontal wall of caches at y = 1, 4 x 4 m, facing down, 0.2 m apart */
    for (int i = 0; i < SIDE * SIDE; i++)
        caches[1 + i] = (light_cache){{-2.0f + 0.2f * (i % SIDE), 1, -2.0f + 0.2f * (i / SIDE)},
                                      {0, -1, 0}, 0.04f, 1};
    cache_proxy p = {{0.1f, 2, 0.1f}, 0.3f, {1, 1, 1}, 1};
    float blocked = cache_occlusion(caches, 1 + SIDE * SIDE, 0, &p);
    float open = cache_occlusion(caches, 1, 0, &p);
    cache_proxy below = {{0.1f, 0.8f, 0.1f}, 0.1f, {1, 1, 1}, 1}; /* nearer than the wall */
    float before = cache_occlusion(caches, 1 + SIDE * SIDE, 0, &below);
    print_message("visibility: through the wall %.3f, no wall %.3f, light before it %.3f\n",
                  blocked, open, before);
    assert_true(blocked < 0.05f);
    assert_true(open == 1.0f);
    assert_true(before == 1.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_density_and_area),
        cmocka_unit_test(test_every_point_reached),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test_setup_teardown(test_file_cases, setup_dir, teardown_dir),
        cmocka_unit_test_setup_teardown(test_unwritable, setup_dir, teardown_dir),
        cmocka_unit_test(test_sat_against_brute_force),
        cmocka_unit_test(test_unbiased_on_emitter_square),
        cmocka_unit_test(test_glossy_proxy),
        cmocka_unit_test(test_occlusion_by_a_wall),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
