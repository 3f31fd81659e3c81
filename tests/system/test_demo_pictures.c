/* The demo's pictures: scripts/demo.sh, run as written on the built programs (with
 * --keep-frames, and any free port instead of the config's), must show every wall lit in
 * every frame. For each screen and eye of configs/clusters/cave5-local.json and each of
 * the 48 frames, the image's mean luma, its share of dark pixels and its spread are
 * checked: a wall the lamp leaves black (the old demo's right-back wall, mean 0) or a flat
 * field fails. The figures of every image are printed, the worst of each kind last. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/cluster_config.h"
#include "image/image.h"

enum { DEMO_FRAMES = 48 };           /* scripts/demo.sh's --frames */
#define MIN_MEAN 32.0                /* display luma, 0..255: a lit wall, not a dim one */
#define DARK_LUMA 16.0               /* a pixel darker than this shows nothing */
#define MAX_DARK 0.10                /* share of such pixels an image may have */
#define MIN_SPREAD 4.0               /* luma standard deviation: detail, not a flat field */

typedef struct picture_stats {
    double mean, dark, spread;
} picture_stats;

static void measure(const uint8_t *rgb, int w, int h, picture_stats *st)
{
    double sum = 0, sum2 = 0;
    size_t dark = 0, n = (size_t)w * h;
    for (size_t i = 0; i < n; i++) {
        double y = 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
        sum += y;
        sum2 += y * y;
        dark += y < DARK_LUMA;
    }
    st->mean = sum / n;
    st->spread = sqrt(fmax(sum2 / n - st->mean * st->mean, 0.0));
    st->dark = (double)dark / n;
}

static void test_every_wall_lit_in_every_frame(void **state)
{
    (void)state;
    char out[] = "/tmp/cavelight-demo-XXXXXX", cmd[2048], err[512];
    assert_non_null(mkdtemp(out));
    snprintf(cmd, sizeof cmd, "CAVELIGHT_BUILD='%s' bash '%s/scripts/demo.sh' '%s' --keep-frames "
             "--bind 'tcp://127.0.0.1:*' > '%s/demo.log' 2>&1", CAVELIGHT_BINARY_DIR, CAVELIGHT_SOURCE_DIR,
             out, out);
    if (system(cmd) != 0) {
        snprintf(cmd, sizeof cmd, "tail -20 '%s/demo.log'", out);
        (void)system(cmd);
        fail_msg("scripts/demo.sh failed");
    }
    static cluster_config cfg;
    if (cluster_config_load(CAVELIGHT_SOURCE_DIR "/configs/clusters/cave5-local.json", &cfg, err, sizeof err))
        fail_msg("%s", err);
    static const char *const eyes[2] = {"left", "right"};
    picture_stats worst = {.mean = 1e9, .spread = 1e9};
    int images = 0, bad = 0;
    for (int s = 0; s < cfg.screen_count; s++)
        for (int e = 0; e < 2; e++)
            for (int f = 1; f <= DEMO_FRAMES; f++) {
                char path[600];
                snprintf(path, sizeof path, "%s/%s-%s-%06d.png", out, cfg.screens[s].name, eyes[e], f);
                int w, h;
                uint8_t *rgb;
                if (image_read_png(path, &w, &h, &rgb, err, sizeof err) != 0)
                    fail_msg("%s", err);
                picture_stats st;
                measure(rgb, w, h, &st);
                free(rgb);
                images++;
                worst.mean = fmin(worst.mean, st.mean);
                worst.dark = fmax(worst.dark, st.dark);
                worst.spread = fmin(worst.spread, st.spread);
                if (st.mean < MIN_MEAN || st.dark > MAX_DARK || st.spread < MIN_SPREAD) {
                    bad++;
                    printf("not lit: %s-%s frame %d: mean %.1f, dark %.3f, spread %.1f\n",
                           cfg.screens[s].name, eyes[e], f, st.mean, st.dark, st.spread);
                }
            }
    printf("%d images: lowest mean %.1f (>= %g), most dark pixels %.3f (<= %g), lowest spread %.1f "
           "(>= %g)\n", images, worst.mean, MIN_MEAN, worst.dark, MAX_DARK, worst.spread, MIN_SPREAD);
    assert_int_equal(images, cfg.screen_count * 2 * DEMO_FRAMES);
    assert_int_equal(bad, 0);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", out);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_wall_lit_in_every_frame),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
