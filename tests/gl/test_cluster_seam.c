/* Seams: adjacent CAVE screens rendered for one head position agree along their shared
 * edge. One node serves the two front half walls and the front half of the floor (one
 * frame pass, three off-axis eye passes, as a cluster node does); the pixels on both
 * sides of each shared edge must differ no more than neighbouring pixels inside one
 * screen do, and much less than unrelated columns; with ILPV, with the vpl method (64
 * VPLs) and with the caches method (512 VALs chosen from the head, not a screen), which
 * the frames switch to as the master's would. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gi/gi_settings.h"

#include "cluster_view.h"
#include "cluster/params.h"

static const char *config_json =
    "{\"master\": {\"bind\": \"tcp://127.0.0.1:1\", \"connect\": \"tcp://127.0.0.1:1\"},"
    " \"security\": {\"mode\": \"insecure\"},"
    " \"observer\": {\"eye_separation\": 0.064, \"head_to_eye\": [0, -0.06, -0.08]},"
    " \"screens\": ["
    "  {\"name\": \"front-l\", \"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [0,0,-1.5], \"top_left\": [-1.5,3,-1.5]},"
    "  {\"name\": \"front-r\", \"bottom_left\": [0,0,-1.5], \"bottom_right\": [1.5,0,-1.5], \"top_left\": [0,3,-1.5]},"
    "  {\"name\": \"floor-f\", \"bottom_left\": [-1.5,0,0], \"bottom_right\": [1.5,0,0], \"top_left\": [-1.5,0,-1.5]}],"
    " \"nodes\": [{\"name\": \"n\", \"eyes\": \"stereo\", \"output\": \"headless\", \"screens\": ["
    "   {\"name\": \"front-l\", \"resolution\": [64, 128]}, {\"name\": \"front-r\", \"resolution\": [64, 128]},"
    "   {\"name\": \"floor-f\", \"resolution\": [128, 64]}]}]}";

/* Mean absolute difference (0..255) between two pixel runs given by start and stride. */
static double run_diff(const uint8_t *a, size_t sa, const uint8_t *b, size_t sb, int n)
{
    double sum = 0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            sum += abs((int)a[i * sa + c] - (int)b[i * sb + c]);
    return sum / (3.0 * n);
}

/* One frame of f on every screen of v; the seams of both eyes. */
static void check_seams(cluster_view *v, const frame_params *f)
{
    char err[512];
    uint64_t checksum;
    float timings[WIRE_TIMING_COUNT] = {0};
    int fixed;
    if (cluster_view_render(v, f, &checksum, timings, &fixed, err, sizeof err) != 0)
        fail_msg("%s", err);
    for (int eye = 0; eye < 2; eye++) {
        int wl, hl, wr, hr, wf, hf;
        const uint8_t *l = cluster_view_image(v, 0, eye, &wl, &hl);
        const uint8_t *r = cluster_view_image(v, 1, eye, &wr, &hr);
        const uint8_t *fl = cluster_view_image(v, 2, eye, &wf, &hf);
        size_t row_l = (size_t)wl * 3, row_r = (size_t)wr * 3;
        /* Vertical seam: last column of front-l against first column of front-r. */
        double seam = run_diff(l + (wl - 1) * 3, row_l, r, row_r, hl);
        double inside = run_diff(l + (wl - 2) * 3, row_l, l + (wl - 1) * 3, row_l, hl);
        double unrelated = run_diff(l, row_l, r + (wr - 1) * 3, row_r, hl);
        /* Horizontal seam: bottom row of front-l against the left half of the floor's top row. */
        double seam_h = run_diff(l + (size_t)(hl - 1) * row_l, 3, fl, 3, wl);
        double inside_h = run_diff(l + (size_t)(hl - 2) * row_l, 3, l + (size_t)(hl - 1) * row_l, 3, wl);
        double unrelated_h = run_diff(l, 3, fl + (size_t)(hf - 1) * wf * 3, 3, wl);
        print_message("eye %d: vertical seam %.2f (inside %.2f, unrelated %.2f); floor seam %.2f (inside %.2f, "
                      "unrelated %.2f)\n", eye, seam, inside, unrelated, seam_h, inside_h, unrelated_h);
        assert_true(seam <= 2.0 * inside + 3.0);
        assert_true(seam_h <= 2.0 * inside_h + 3.0);
        assert_true(unrelated > 3.0 * seam + 2.0);
        assert_true(unrelated_h > 3.0 * seam_h + 2.0);
    }
}

static void test_seams_agree(void **state)
{
    static cluster_config cfg;
    char err[512];
    assert_int_equal(cluster_config_parse(config_json, strlen(config_json), "seam.json", &cfg, err, sizeof err), 0);
    cluster_view_desc vd = {.config = &cfg, .node = 0, .output = CLUSTER_OUTPUT_HEADLESS, .threads = 2};
    cluster_view *v = cluster_view_create(&vd, err, sizeof err);
    if (!v)
        fail_msg("%s", err);
    static params_schema schema;
    static params_store ps;
    gi_params_schema(&schema);
    params_init(&ps, &schema);
    frame_params f;
    params_to_frame(&ps, &f);
    assert_null(gi_set(&f, "lattice", "20"));
    assert_null(gi_set(&f, "rsm", "128"));
    assert_null(gi_set(&f, "vpl-count", "64"));
    assert_null(gi_set(&f, "caches-vals", "512"));
    /* Head off-centre and turned: the seams are seen at an angle. */
    float head[16] = {0.955f, 0, 0.296f, 0, 0, 1, 0, 0, -0.296f, 0, 0.955f, 0, 0.4f, 1.6f, 0.3f, 1};
    memcpy(f.head, head, sizeof head);
    f.light_count = 1;
    f.lights[0] = (frame_light){.enabled = 1, .position = {0.5f, 2.8f, -0.5f}, .direction = {-0.3f, -0.95f, 0},
                                .color = {1, 1, 1}, .intensity = 20, .outer_angle = 0.8f, .inner_angle = 0.6f};
    const char *methods[3] = {"ilpv", "vpl", "caches"};
    for (int k = 0; k < 3; k++) {
        f.gi = gi_method_find(methods[k]);
        print_message("%s:\n", gi_method_at(f.gi)->name);
        check_seams(v, &f);
    }
    cluster_view_destroy(v);
}

static void test_view_maths(void **state)
{
    static cluster_config cfg;
    char err[512];
    assert_int_equal(cluster_config_parse(config_json, strlen(config_json), "seam.json", &cfg, err, sizeof err), 0);
    static params_schema schema;
    static params_store ps;
    gi_params_schema(&schema);
    params_init(&ps, &schema);
    frame_params f;
    params_to_frame(&ps, &f);
    float head[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1.7f, 0, 1};
    memcpy(f.head, head, sizeof head);
    renderer_view lv, rv;
    assert_int_equal(cluster_view_compute(&cfg, 0, -1, &f, 64, 128, 100, &lv, NULL), 0);
    assert_int_equal(cluster_view_compute(&cfg, 0, 1, &f, 64, 128, 100, &rv, NULL), 0);
    /* Eyes 6.4 cm apart along the head's right axis, 6 cm below and 8 cm in front of the sensor. */
    assert_float_equal(rv.eye_position[0] - lv.eye_position[0], 0.064f, 1e-6);
    assert_float_equal(lv.eye_position[1], 1.64f, 1e-6);
    assert_float_equal(lv.eye_position[2], -0.08f, 1e-6);
    /* Navigation moves the world, not the picture: eye and screens move together. */
    f.navigation[12] = 5;
    renderer_view nv;
    assert_int_equal(cluster_view_compute(&cfg, 0, -1, &f, 64, 128, 100, &nv, NULL), 0);
    assert_float_equal(nv.eye_position[0], lv.eye_position[0] + 5, 1e-5);
    for (int i = 0; i < 16; i++)
        assert_float_equal(nv.projection[i], lv.projection[i], 1e-4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_view_maths),
        cmocka_unit_test(test_seams_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
