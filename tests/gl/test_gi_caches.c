/* The caches GI method on llvmpipe against its host copy (common/gi/caches/), on the default
 * room:
 *   selection: the GPU's importance, summed-area tables and binary search pick what the
 *     host's val_select.h picks from the RSMs read back and the same view samples (nearly
 *     every slot alike; float sums may move a boundary), each texel within 2.5 of n p times
 *     and with weight 1 / (n p);
 *   proxies: the GPU's proxy lights are cache_proxy_gather() of the VALs it selected, and
 *     its occlusion is cache_occlusion();
 *   interpolation: each pixel's indirect light is cache_interpolate() at the point the
 *     pixel sees, and it has no visible cache structure: against the same VALs gathered at
 *     every pixel (a cache at every pixel), the high-frequency part of the difference
 *     (difference less its 5 x 5 mean, inside flat regions) is a few percent of the light;
 *   the disk cache: a second renderer reads the caches the first placed;
 *   glossy (caches-glossy on): the GPU's glossy proxies are cache_glossy_gather() of its
 *     VALs for its viewer, each pixel's glossy term is cache_interpolate_glossy(); moving
 *     the head changes the glossy proxies and image of smooth surfaces but not the diffuse
 *     ones (every RSM texel a VAL: no view-dependent selection), turning glossy off again
 *     gives the image of before bit for bit, and rough surfaces' glossy term is small. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <unistd.h>

#include "base/vec3.h"
#include "gl/gl_testutil.h"
#include "gi/caches/gi_caches.h"
#include "renderer_rsm.h"
#include "reference/scene_rt.h"
#include "gi/view_samples.h"
#include "gi/vpl_source.h"

enum { W = 64, H = 48, VALS = 1024 };

static char cache_dir[256];

static int setup(void **state)
{
    (void)state;
    snprintf(cache_dir, sizeof cache_dir, "%s/test_gi_caches.%ld", CAVELIGHT_BINARY_DIR,
             (long)getpid());
    setenv("CAVELIGHT_CACHE_DIR", cache_dir, 1);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cache_dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* The default room with caches: 64 RSM, VALS VALs, occlusion as given, a head off centre. */
static void open_caches(gltest *t, const char *occlusion)
{
    assert_int_equal(gltest_open(t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    t->params.gi = gi_method_find("caches");
    gltest_setn(&t->params, "caches-vals", VALS);
    gltest_set(&t->params, "caches-occlusion", occlusion);
    const float head[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.8f, 1.5f, 0.6f, 1};
    memcpy(t->params.head, head, sizeof head);
}

static void view(renderer_view *v)
{
    const float eye[3] = {1.3f, 1.6f, 1.9f}, target[3] = {-0.5f, 0.9f, -1.2f};
    gltest_look_at(v, eye, target, 1.15f, W, H);
}

/* One frame of t->params; the indirect image (W x H x 3) into out when given. */
static gi_caches *frame(gltest *t, float *out)
{
    renderer_frame_pass(t->r, &t->params);
    renderer_view v;
    view(&v);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t->r, &v, 1, &img), 0);
    if (out)
        memcpy(out, img.indirect, sizeof(float) * W * H * 3);
    gi_caches *c = gi_caches_of(renderer_gi(t->r));
    assert_non_null(c);
    return c;
}

/* The host's importance of every texel (column-major pairs, as val_select.h) from the RSMs
 * read back and the view samples from the head. Returns columns; *rows the size. */
static int host_importance(gltest *t, float **imp, int *rows)
{
    const gl_functions *gl = glctx_gl(t->ctx);
    renderer_rsm *m = renderer_get_rsm(t->r);
    int size = renderer_rsm_size(m), layers = renderer_rsm_views(m, NULL, NULL);
    GLuint tex[3];
    renderer_rsm_textures(m, tex);
    size_t texels = (size_t)size * size * layers;
    float *maps[3];
    for (int k = 0; k < 3; k++) {
        maps[k] = malloc(texels * 4 * sizeof(float));
        gl->BindTexture(GL_TEXTURE_2D_ARRAY, tex[k]);
        gl->GetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA, GL_FLOAT, maps[k]);
    }
    char err[256];
    view_samples *vs = view_samples_create(&t->scene, VIEW_SAMPLES_MAX, err, sizeof err);
    assert_non_null(vs);
    float eye[3], zero[3] = {0, 0, 0};
    frame_view_head_centre(t->params.head, zero, eye);
    const float *samples;
    int ns = view_samples_cast(vs, eye, CACHES_VIEW_SAMPLES_DEFAULT, &samples);
    *imp = malloc(texels * 2 * sizeof(float));
    for (int l = 0; l < layers; l++)
        for (int y = 0; y < size; y++)
            for (int x = 0; x < size; x++) {
                size_t i = ((size_t)l * size + y) * size + x, layer = (size_t)l * size * size;
                vpl v;
                memcpy(v.position, maps[0] + 4 * i, sizeof v.position);
                memcpy(v.normal, maps[1] + 4 * i, sizeof v.normal);
                for (int k = 0; k < 3; k++)
                    v.flux[k] = maps[0][4 * i + 3] == 0 ? 0 : fmaxf(maps[2][4 * i + k], 0);
                v.area = vpl_texel_area(maps[0] + 4 * layer, maps[1] + 4 * layer, size, x, y);
                val_importance(&v, samples, ns, *imp + 2 * (((size_t)l * size + x) * size + y));
            }
    view_samples_destroy(vs);
    for (int k = 0; k < 3; k++)
        free(maps[k]);
    *rows = size;
    return size * layers;
}

static void test_selection_matches_host(void **state)
{
    (void)state;
    gltest t;
    open_caches(&t, "approx");
    gi_caches *c = frame(&t, NULL);
    const val_pick *gpu;
    assert_int_equal(gi_caches_picks(c, &gpu), VALS);
    float *imp;
    int rows, columns = host_importance(&t, &imp, &rows);
    size_t texels = (size_t)columns * rows;
    double qv = 0, qf = 0;
    for (size_t j = 0; j < texels; j++)
        qv += imp[2 * j], qf += imp[2 * j + 1];
    float *sums = malloc(texels * 2 * sizeof *sums), *row = malloc((size_t)columns * 2 * sizeof *row);
    memcpy(sums, imp, texels * 2 * sizeof *sums);
    val_sat_build(sums, columns, rows, row);
    static val_pick host[VALS];
    assert_int_equal(val_sat_select(sums, row, columns, rows, VALS, 0, host), VALS);
    int same = 0;
    int *count = calloc(texels, sizeof *count);
    double worst_weight = 0;
    for (int i = 0; i < VALS; i++) {
        same += gpu[i].column == host[i].column && gpu[i].row == host[i].row;
        size_t j = (size_t)gpu[i].column * rows + gpu[i].row;
        count[j]++;
        double p = 0.5 * (imp[2 * j] / qv + imp[2 * j + 1] / qf);
        assert_true(p > 0);
        worst_weight = fmax(worst_weight, fabs(gpu[i].weight * VALS * p - 1));
    }
    double worst = 0;
    for (size_t j = 0; j < texels; j++)
        worst = fmax(worst, fabs(count[j] - VALS * 0.5 * (imp[2 * j] / qv + imp[2 * j + 1] / qf)));
    print_message("%d of %d slots pick the host's texel; largest |count - n p| %.3f; largest "
                  "|weight n p - 1| %.2g\n", same, VALS, worst, worst_weight);
    assert_true(same >= VALS * 95 / 100);
    assert_true(worst <= 2.5);
    assert_true(worst_weight < 1e-3);
    free(count);
    free(sums);
    free(row);
    free(imp);
    gltest_close(&t);
}

/* The GPU's proxies against the host's from the same VALs (and the same occlusion). */
static void compare_proxies(gi_caches *c, int occluded)
{
    const vpl *vals;
    size_t n = gi_caches_vals(c, &vals);
    const cache_set *set = gi_caches_set(c);
    const cache_proxy *gpu = gi_caches_proxies(c);
    size_t off = 0, vis_off = 0;
    double largest = 0;
    for (size_t i = 0; i < set->count; i++) {
        cache_proxy host;
        cache_proxy_gather(&set->caches[i], vals, n, NULL, &host);
        float vis = occluded ? cache_occlusion(set->caches, set->count, i, &host) : 1.0f;
        vis_off += fabsf(vis - gpu[i].visibility) > 1e-3f;
        for (int k = 0; k < 3; k++)
            largest = fmax(largest, host.irradiance[k]);
        float e0 = host.irradiance[0] * vis, e1 = gpu[i].irradiance[0];
        off += fabsf(e0 - e1) > 1e-3f * fabsf(e0) + 1e-6f;
    }
    print_message("%zu caches, %zu VALs: %zu irradiances and %zu visibilities off the host's "
                  "(largest E %.3g)\n", set->count, n, off, vis_off, largest);
    assert_true(largest > 0);
    assert_true(off <= set->count / 100);
    assert_true(vis_off <= set->count / 100);
}

static void test_proxies_match_host(void **state)
{
    (void)state;
    for (int occluded = 0; occluded < 2; occluded++) {
        gltest t;
        open_caches(&t, occluded ? "approx" : "off");
        compare_proxies(frame(&t, NULL), occluded);
        gltest_close(&t);
    }
}

/* What pixel (x, y) of view() sees: point, unit normal (to the eye) and albedo; 0 if none. */
static int pixel_hit(const scene_rt *rt, const scene *s, int x, int y, float p[3], float n[3],
                     float albedo[3])
{
    renderer_view v;
    view(&v);
    float ndc[2] = {2 * (x + 0.5f) / W - 1, 1 - 2 * (y + 0.5f) / H}, d[3];
    float t = tanf(0.5f * 1.15f);
    for (int k = 0; k < 3; k++)
        d[k] = -v.view[4 * k + 2] + ndc[0] * t * W / H * v.view[4 * k] + ndc[1] * t * v.view[4 * k + 1];
    vec3_normalize(d);
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh = {
        .ray = {.org_x = v.eye_position[0], .org_y = v.eye_position[1], .org_z = v.eye_position[2],
                .dir_x = d[0], .dir_y = d[1], .dir_z = d[2], .tfar = INFINITY, .mask = ~0u},
        .hit = {.geomID = RTC_INVALID_GEOMETRY_ID}};
    scene_rt_intersect(rt, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return 0;
    vec3_triangle_normal(s->positions + 9 * rh.hit.primID, n);
    vec3_normalize(n);
    if (vec3_dot(n, d) > 0)
        for (int k = 0; k < 3; k++)
            n[k] = -n[k];
    for (int k = 0; k < 3; k++) {
        p[k] = v.eye_position[k] + rh.ray.tfar * d[k];
        albedo[k] = s->materials[s->triangle_material[rh.hit.primID]].base_color[k];
    }
    return 1 + (int)rh.hit.primID;
}

static float lum(const float *c) { return c[0] + c[1] + c[2]; }

static void test_interpolation(void **state)
{
    (void)state;
    gltest t;
    open_caches(&t, "off");
    static float img[W * H * 3], interp[W * H], gather[W * H];
    static int plane[W * H];
    gi_caches *c = frame(&t, img);
    const vpl *vals;
    size_t n = gi_caches_vals(c, &vals);
    scene_rt rt;
    char err[256];
    assert_int_equal(scene_rt_build(&rt, &t.scene, 0, err, sizeof err), 0);
    int agree = 0, hits = 0;
    double mean = 0;
    for (int i = 0; i < W * H; i++) {
        float p[3], nrm[3], albedo[3];
        plane[i] = pixel_hit(&rt, &t.scene, i % W, i / W, p, nrm, albedo);
        if (!plane[i])
            continue;
        /* the plane of the hit triangle, so that two triangles of one quad are one region */
        plane[i] = (int)(nrm[0] * 3 + 4) * 100000 + (int)(nrm[1] * 3 + 4) * 10000 +
                   (int)(nrm[2] * 3 + 4) * 1000 + (int)floorf(vec3_dot(nrm, p) * 50 + 500);
        float e[3], host[3], shaded[3];
        light_cache at = {{p[0], p[1], p[2]}, {nrm[0], nrm[1], nrm[2]}, 0, 1};
        cache_proxy g;
        cache_proxy_gather(&at, vals, n, NULL, &g);
        cache_interpolate(gi_caches_grid(c), gi_caches_set(c)->caches, gi_caches_hidden(c),
                          gi_caches_proxies(c), p, nrm, host);
        for (int k = 0; k < 3; k++) {
            e[k] = albedo[k] / 3.14159265f * g.irradiance[k];
            shaded[k] = albedo[k] / 3.14159265f * host[k];
        }
        interp[i] = lum(img + 3 * i);
        gather[i] = lum(e);
        mean += gather[i];
        hits++;
        agree += fabsf(interp[i] - lum(shaded)) <= 0.01f * lum(shaded) + 1e-6f;
    }
    mean /= hits;
    /* high frequencies of the difference inside flat regions */
    double hf = 0, low = 0;
    int counted = 0;
    for (int y = 2; y < H - 2; y++)
        for (int x = 2; x < W - 2; x++) {
            int i = y * W + x, flat = plane[i] != 0;
            double local = 0;
            for (int dy = -2; dy <= 2 && flat; dy++)
                for (int dx = -2; dx <= 2; dx++) {
                    int j = i + dy * W + dx;
                    flat = flat && plane[j] == plane[i];
                    local += interp[j] - gather[j];
                }
            if (!flat)
                continue;
            double d = interp[i] - gather[i], h = d - local / 25;
            hf += h * h;
            low += d * d;
            counted++;
        }
    double blotch = sqrt(hf / counted) / mean, smooth = sqrt(low / counted) / mean;
    print_message("%d of %d pixels are the host's interpolation within 1%%; against a cache "
                  "at every pixel: high-frequency difference %.4f, whole difference %.4f of "
                  "the mean (%d flat pixels)\n", agree, hits, blotch, smooth, counted);
    assert_true(agree >= hits * 95 / 100);
    assert_true(counted > W * H / 4);
    assert_true(blotch < 0.012); /* nearest cache only: 0.022 */
    assert_true(smooth < 0.25);
    scene_rt_release(&rt);
    gltest_close(&t);
}

/* The GPU's glossy proxies against the host's for the same VALs and viewer; occluded (approx):
 * times the host's diffuse proxy's visibility. */
static void compare_glossy(gi_caches *c, int occluded)
{
    const vpl *vals;
    size_t n = gi_caches_vals(c, &vals);
    const cache_set *set = gi_caches_set(c);
    const cache_proxy *gpu = gi_caches_glossy(c);
    size_t off = 0, moved = 0, lit = 0, apart = 0;
    for (size_t i = 0; i < set->count; i++) {
        cache_proxy host, diffuse;
        cache_glossy_gather(&set->caches[i], gi_caches_viewer(c), vals, n, NULL, &host);
        cache_proxy_gather(&set->caches[i], vals, n, NULL, &diffuse);
        float vis = occluded ? cache_occlusion(set->caches, set->count, i, &diffuse) : 1.0f;
        float e0 = host.irradiance[0] * vis, e1 = gpu[i].irradiance[0], d[3], s[3];
        off += fabsf(e0 - e1) > 2e-3f * fabsf(e0) + 1e-6f;
        vec3_sub(host.position, gpu[i].position, d);
        vec3_sub(host.position, diffuse.position, s);
        moved += vec3_length(d) > 1e-3f;
        apart += vec3_length(s) > 0.05f;
        lit += e0 > 0;
    }
    print_message("%zu caches (%zu lit, %zu glossy proxies 5 cm or more from the diffuse "
                  "one): %zu glossy irradiances and %zu positions off the host's\n",
                  set->count, lit, apart, off, moved);
    assert_true(lit > set->count / 2);
    assert_true(apart > set->count / 10);
    assert_true(off <= set->count / 100);
    assert_true(moved <= set->count / 100);
}

static void test_glossy_proxies_match_host(void **state)
{
    (void)state;
    for (int occluded = 0; occluded < 2; occluded++) {
        gltest t;
        open_caches(&t, occluded ? "approx" : "off");
        gltest_set(&t.params, "caches-glossy", "on");
        compare_glossy(frame(&t, NULL), occluded);
        gltest_close(&t);
    }
}

/* Each pixel's indirect light (img) is the host's diffuse interpolation times albedo / pi
 * plus its glossy interpolation, for the eye of view(). */
static void glossy_pixels_match(gltest *t, gi_caches *c, const float *img)
{
    scene_rt rt;
    char err[256];
    assert_int_equal(scene_rt_build(&rt, &t->scene, 0, err, sizeof err), 0);
    renderer_view v;
    view(&v);
    int agree = 0, agree_glossy = 0, hits = 0;
    double glossy = 0, diffuse = 0;
    for (int i = 0; i < W * H; i++) {
        float p[3], nrm[3], albedo[3], e[3], g[3], to_eye[3];
        int hit = pixel_hit(&rt, &t->scene, i % W, i / W, p, nrm, albedo);
        if (!hit)
            continue;
        float rough = t->scene.materials[t->scene.triangle_material[hit - 1]].roughness;
        vec3_sub(v.eye_position, p, to_eye);
        vec3_normalize(to_eye);
        cache_interpolate(gi_caches_grid(c), gi_caches_set(c)->caches, gi_caches_hidden(c),
                          gi_caches_proxies(c), p, nrm, e);
        cache_interpolate_glossy(gi_caches_grid(c), gi_caches_set(c)->caches,
                                 gi_caches_hidden(c), gi_caches_glossy(c), p, nrm, rough,
                                 to_eye, g);
        float want[3];
        for (int k = 0; k < 3; k++)
            want[k] = albedo[k] / 3.14159265f * e[k] + g[k];
        hits++;
        glossy += lum(g);
        diffuse += lum(want) - lum(g);
        agree += fabsf(lum(img + 3 * i) - lum(want)) <= 0.01f * lum(want) + 1e-6f;
        /* the glossy term alone: the image less the host's diffuse term, with the albedo
         * as the G-buffer holds it (8 bits) */
        float gpu = lum(img + 3 * i);
        for (int k = 0; k < 3; k++)
            gpu -= roundf(albedo[k] * 255) / 255 / 3.14159265f * e[k];
        /* 3% of it, and what the diffuse term leaves (its half-float inputs: ~0.2%) */
        agree_glossy += fabsf(gpu - lum(g)) <= 0.03f * lum(g) + 3e-3f * lum(want) + 1e-6f;
    }
    print_message("%d of %d pixels are the host's diffuse and glossy interpolation within 1%%, "
                  "%d their glossy term within 3%% (glossy %.1f%% of the indirect light)\n",
                  agree, hits, agree_glossy, 100 * glossy / (glossy + diffuse));
    assert_true(agree >= hits * 95 / 100);
    /* all but 0.2%: equation 8's reflection weight, taken as the diffuse one, leaves 0.7% */
    assert_true(agree_glossy >= hits - hits / 500);
    assert_true(glossy > 0.01 * diffuse);
    scene_rt_release(&rt);
}

static void test_glossy_pixels(void **state)
{
    (void)state;
    gltest t;
    open_caches(&t, "off");
    gltest_set(&t.params, "caches-glossy", "on");
    static float img[W * H * 3];
    glossy_pixels_match(&t, frame(&t, img), img);
    gltest_close(&t);
}

/* Every material at roughness r, placed again (another density: a rebuild); every RSM
 * texel a VAL, so that only the glossy proxies follow the head. */
static void open_rough(gltest *t, float r)
{
    open_caches(t, "off");
    for (size_t i = 0; i < t->scene.material_count; i++)
        t->scene.materials[i].roughness = r;
    gltest_set(&t->params, "caches-selection", "all");
    gltest_setn(&t->params, "caches-density", 12);
}

/* The glossy term (image with glossy on less the one with it off) into out; its luminance
 * sum, and the diffuse one's into *diffuse. */
static double glossy_term(const float *on, const float *off, float *out, double *diffuse)
{
    double sum = 0;
    *diffuse = 0;
    for (int i = 0; i < W * H * 3; i++) {
        out[i] = on[i] - off[i];
        sum += out[i];
        *diffuse += off[i];
    }
    return sum;
}

static void test_glossy_view_dependent(void **state)
{
    (void)state;
    gltest t;
    open_rough(&t, 0.3f);
    static float off[W * H * 3], again[W * H * 3], on[2][W * H * 3], g[2][W * H * 3];
    gi_caches *c = frame(&t, off);
    size_t count = gi_caches_set(c)->count;
    assert_true(fabsf(gi_caches_set(c)->caches[0].roughness - 0.3f) < 1e-5f);
    cache_proxy *diffuse[2], *glossy[2];
    double sum[2], dsum = 0, change = 0, peak = 0;
    gltest_set(&t.params, "caches-glossy", "on");
    for (int k = 0; k < 2; k++) {
        t.params.head[12] = k ? -1.2f : 0.8f; /* the head 2 m to the side */
        c = frame(&t, on[k]);
        glossy_pixels_match(&t, c, on[k]); /* smooth: the caches' proxies differ more */
        diffuse[k] = malloc(count * sizeof **diffuse);
        glossy[k] = malloc(count * sizeof **glossy);
        memcpy(diffuse[k], gi_caches_proxies(c), count * sizeof **diffuse);
        memcpy(glossy[k], gi_caches_glossy(c), count * sizeof **glossy);
        sum[k] = glossy_term(on[k], off, g[k], &dsum);
    }
    for (int i = 0; i < W * H * 3; i++) {
        change += fabs(g[1][i] - g[0][i]);
        peak = fmax(peak, g[0][i] / fmax(off[i], 1e-6));
    }
    gltest_set(&t.params, "caches-glossy", "off");
    frame(&t, again);
    print_message("roughness 0.3: glossy %.1f%% of the diffuse light, at most %.2f times it; "
                  "moving the head changes it by %.1f%%\n", 100 * sum[0] / dsum, peak,
                  100 * change / sum[0]);
    assert_memory_equal(diffuse[0], diffuse[1], count * sizeof **diffuse);
    assert_true(memcmp(glossy[0], glossy[1], count * sizeof **glossy) != 0);
    assert_true(change > 0.2 * sum[0]);
    assert_true(peak > 0.5);
    assert_memory_equal(off, again, sizeof off);
    for (int k = 0; k < 2; k++)
        free(diffuse[k]), free(glossy[k]);
    gltest_close(&t);
}

static void test_glossy_rough_is_small(void **state)
{
    (void)state;
    gltest t;
    open_rough(&t, 1.0f);
    static float off[W * H * 3], on[W * H * 3], g[W * H * 3];
    frame(&t, off);
    gltest_set(&t.params, "caches-glossy", "on");
    frame(&t, on);
    double diffuse, glossy = glossy_term(on, off, g, &diffuse);
    print_message("roughness 1: glossy %.1f%% of the diffuse light\n", 100 * glossy / diffuse);
    assert_true(glossy > 0);
    assert_true(glossy < 0.1 * diffuse);
    gltest_close(&t);
}

static void test_disk_cache(void **state)
{
    (void)state;
    gltest t;
    open_caches(&t, "off");
    gi_caches *c = frame(&t, NULL);
    const cache_set *first = gi_caches_set(c);
    size_t count = first->count;
    light_cache *copy = malloc(count * sizeof *copy);
    memcpy(copy, first->caches, count * sizeof *copy);
    print_message("first: %s, %.1f ms\n", gi_caches_store(c)->from_file ? "read" : "placed",
                  gi_caches_store(c)->ms);
    gltest_close(&t);
    open_caches(&t, "off");
    c = frame(&t, NULL);
    print_message("second: %s, %.1f ms\n", gi_caches_store(c)->from_file ? "read" : "placed",
                  gi_caches_store(c)->ms);
    assert_int_equal(gi_caches_store(c)->from_file, 1);
    assert_int_equal(gi_caches_set(c)->count, count);
    assert_memory_equal(gi_caches_set(c)->caches, copy, count * sizeof *copy);
    free(copy);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_selection_matches_host),
        cmocka_unit_test(test_proxies_match_host),
        cmocka_unit_test(test_interpolation),
        cmocka_unit_test(test_disk_cache),
        cmocka_unit_test(test_glossy_proxies_match_host),
        cmocka_unit_test(test_glossy_pixels),
        cmocka_unit_test(test_glossy_view_dependent),
        cmocka_unit_test(test_glossy_rough_is_small),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
